#include "parameter_file.h"

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace talus
{

namespace
{

std::string trim(const std::string& s)
{
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos)
    return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

/// Collapses runs of blanks, as ParameterHandler does for names.
std::string collapse(const std::string& s)
{
  std::string out;
  for (char c : trim(s))
    if (!(c == ' ' || c == '\t') || out.empty() || out.back() != ' ')
      out.push_back(c == '\t' ? ' ' : c);
  return out;
}

std::string join_path(const std::vector<std::string>& parts)
{
  std::string p;
  for (const auto& s : parts)
    p += (p.empty() ? "" : " / ") + s;
  return p;
}

} // namespace

/// Deepest nesting of 'include' (a cycle is refused before this).
constexpr unsigned int max_include_depth = 16;
/// Largest parameter file read (bytes): a text file of entries is far smaller.
constexpr std::uintmax_t max_file_size = 64u << 20;

void ParameterFile::read_text(const std::string& file, std::vector<std::string>& open_files)
{
  std::error_code ec;
  const bool included = !open_files.empty();
  const std::string what = included ? "included file" : "parameter file";
  if (!std::filesystem::is_regular_file(file, ec))
    throw InputError(file + ": " +
                     (!std::filesystem::exists(file, ec) ? "no such " + what
                      : std::filesystem::is_directory(file, ec)
                          ? "a folder, not a file"
                          : "not a regular file (a device?)") +
                     "; allowed: a readable parameter file (.prm)");
  if (std::filesystem::file_size(file, ec) > max_file_size)
    throw InputError(file + ": the " + what + " has " +
                     std::to_string(std::filesystem::file_size(file, ec)) +
                     " bytes, too many for a parameter file; allowed: at most " +
                     std::to_string(max_file_size) + " bytes");
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw InputError(file + ": cannot open the " + what + " (" + std::strerror(errno) +
                     "); allowed: a readable parameter file (.prm)");
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  if (in.bad())
    throw InputError(file + ": reading the " + what + " failed");
  // A byte-order mark (some Windows editors) and CR or CR LF line ends
  // (old Mac, Windows) are plain text too.
  if (text.rfind("\xEF\xBB\xBF", 0) == 0)
    text.erase(0, 3);
  std::string unix_text;
  unix_text.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i)
    if (text[i] != '\r')
      unix_text.push_back(text[i]);
    else if (i + 1 == text.size() || text[i + 1] != '\n')
      unix_text.push_back('\n');

  std::error_code canonical_error;
  const std::string canonical = std::filesystem::weakly_canonical(file, canonical_error).string();
  open_files.push_back(canonical);
  std::istringstream lines(unix_text);
  std::string line;
  for (unsigned int number = 1; std::getline(lines, line); ++number)
  {
    const std::string here = file + ":" + std::to_string(number);
    for (const char c : line)
      if ((static_cast<unsigned char>(c) < 32 && c != '\t') || c == 127)
      {
        char byte[8];
        std::snprintf(byte, sizeof byte, "0x%02x", static_cast<unsigned char>(c));
        throw InputError(here + ": the line holds a control character (byte " + byte +
                         "), so this is not a text file; allowed: a parameter file of text lines");
      }
    const auto hash = line.find('#');
    const std::string code = trim(hash == std::string::npos ? line : line.substr(0, hash));
    if (code == "include" || code.rfind("include ", 0) == 0 || code.rfind("include\t", 0) == 0)
    {
      const std::string named = trim(code.substr(7));
      if (named.empty())
        throw InputError(here + ": 'include' names no file; allowed: 'include FILE'");
      std::filesystem::path target(named);
      if (target.is_relative())
        target = std::filesystem::path(file).parent_path() / target;
      const std::string name = target.string();
      const std::string target_canonical =
          std::filesystem::weakly_canonical(target, canonical_error).string();
      if (std::find(open_files.begin(), open_files.end(), target_canonical) != open_files.end())
        throw InputError(
            here + ": 'include " + named + "' includes " +
            (target_canonical == canonical ? "this file itself" : "a file that includes this one") +
            "; allowed: includes without a cycle");
      if (open_files.size() >= max_include_depth)
        throw InputError(here + ": includes nest more than " + std::to_string(max_include_depth) +
                         " deep; allowed: at most that many files inside one another");
      try
      {
        read_text(name, open_files);
      }
      catch (const InputError& e)
      {
        // Name the include line too: the problem is in the file it names.
        if (std::string(e.what()).rfind(name + ":", 0) == 0 &&
            std::string(e.what()).find("; allowed: a readable parameter file") != std::string::npos)
          throw InputError(here + ": 'include " + named +
                           "': " + std::string(e.what()).substr(name.size() + 2));
        throw;
      }
      continue;
    }
    text_ += line;
    text_ += '\n';
    origin_.emplace_back(file, number);
  }
  open_files.pop_back();
}

std::string ParameterFile::where(unsigned int line) const
{
  if (line == 0 || line > origin_.size())
    return filename_;
  return origin_[line - 1].first + ":" + std::to_string(origin_[line - 1].second);
}

ParameterFile::ParameterFile(const std::string& filename) : filename_(filename)
{
  std::vector<std::string> open_files;
  read_text(filename, open_files);

  // A lenient first pass that only records where things are; the real parse
  // (and its error reporting) is ParameterHandler's.
  std::istringstream lines(text_);
  std::string line;
  std::vector<std::string> stack;
  bool any_statement = false;
  for (unsigned int number = 1; std::getline(lines, line); ++number)
  {
    const auto hash = line.find('#');
    const std::string code = trim(hash == std::string::npos ? line : line.substr(0, hash));
    if (code.rfind("subsection ", 0) == 0 || code.rfind("subsection\t", 0) == 0)
    {
      stack.push_back(collapse(code.substr(10)));
      const auto [first, fresh] = section_line_.emplace(join_path(stack), number);
      // ParameterHandler would take the later values silently.
      if (!fresh)
        throw InputError(where(number) + ": subsection '" + join_path(stack) +
                         "' is opened a second time (first at " + where(first->second) +
                         "); allowed: each subsection once, with all its entries");
      if (stack.size() == 1) // opened once (above), so listed once
        sections_in_file_.push_back(stack[0]);
    }
    else if (code == "end" && !stack.empty())
      stack.pop_back();
    else if (code.rfind("set ", 0) == 0 || code.rfind("set\t", 0) == 0)
    {
      const auto eq = code.find('=');
      const std::string name = collapse(code.substr(4, eq == std::string::npos ? std::string::npos
                                                                               : eq - 4));
      const std::string value = eq == std::string::npos ? "" : trim(code.substr(eq + 1));
      const auto [first, fresh] =
          entry_line_.emplace(std::make_pair(join_path(stack), name), number);
      if (!fresh)
      {
        const std::string section = join_path(stack);
        const auto [file, at] = origin_[number - 1];
        throw InputError::at(file, at, section, name,
                             "is set a second time (first at " + where(first->second) + ")",
                             "one 'set' per entry");
      }
      line_entry_[number] = {join_path(stack), name, value};
    }
    any_statement |= !code.empty();
  }
  if (!any_statement)
    throw InputError(filename + ": the file is empty (it sets nothing); allowed: a parameter "
                                "file with at least one subsection");
}

void ParameterFile::enter(const std::string& section)
{
  handler_.enter_subsection(section);
  current_.push_back(section);
}

void ParameterFile::leave()
{
  handler_.leave_subsection();
  current_.pop_back();
}

std::string ParameterFile::path() const { return join_path(current_); }

void ParameterFile::declare(const std::string& name, const std::string& default_value,
                            const dealii::Patterns::PatternBase& pattern,
                            const std::string& allowed, const std::string& documentation)
{
  handler_.declare_entry(name, default_value, pattern, documentation);
  declared_[path()].emplace_back(name, allowed);
}

void ParameterFile::parse()
{
  try
  {
    std::istringstream in(text_);
    handler_.parse_input(in, filename_);
  }
  catch (const dealii::ExceptionBase& e)
  {
    rethrow(e);
  }
}

void ParameterFile::rethrow(const dealii::ExceptionBase& e) const
{
  std::ostringstream info;
  e.print_info(info);
  const std::string text = info.str();
  std::smatch m;
  unsigned int line = 0;
  if (std::regex_search(text, m, std::regex("Line <([0-9]+)>")))
    line = static_cast<unsigned int>(std::stoul(m[1]));
  const std::string at = where(line);
  // (file, line) of the statement, in the file that holds it (an include).
  const std::string file = line > 0 && line <= origin_.size() ? origin_[line - 1].first : filename_;
  const unsigned int file_line = line > 0 && line <= origin_.size() ? origin_[line - 1].second : 0;

  // An entry whose value does not fit its pattern: name it and say what fits.
  if (dynamic_cast<const dealii::ParameterHandler::ExcInvalidEntryForPattern*>(&e) &&
      line_entry_.count(line))
  {
    const auto& entry = line_entry_.at(line);
    std::string allowed;
    if (declared_.count(entry[0]))
      for (const auto& d : declared_.at(entry[0]))
        if (d.first == entry[1])
          allowed = d.second;
    throw InputError::at(file, file_line, entry[0], entry[1], "value '" + entry[2] + "' is invalid",
                         allowed);
  }
  // A line that names no declared entry, or is not a statement at all.
  if (std::regex_search(text, m, std::regex("No entry with name <([^>]*)> was declared")))
  {
    const std::string section = line_entry_.count(line) ? line_entry_.at(line)[0] : "";
    std::string names;
    if (declared_.count(section))
      for (const auto& d : declared_.at(section))
        names += (names.empty() ? "" : ", ") + d.first;
    throw InputError::at(file, file_line, section, m[1], "no such entry",
                         names.empty() ? "" : "entries " + names);
  }
  if (std::regex_search(text, m, std::regex("no such subsection to be entered: ([^\n]*)")))
  {
    std::string names;
    for (const auto& d : declared_)
      if (!d.first.empty() && d.first.find(" / ") == std::string::npos)
        names += (names.empty() ? "" : ", ") + d.first;
    throw InputError(at + ": unknown subsection '" + trim(m[1]) + "'; allowed: " + names +
                     " (numbered ones: 'Joint set N', 'Joint N', 'Joint material N', 'Excavation "
                     "N', 'Group N', 'Group contact N', 'Rock material N', 'Load N', 'Boundary N', "
                     "'Stage N' with 'Excavation M' inside)");
  }
  if (std::regex_search(text, m, std::regex("unequal numbers of 'subsection' and 'end'")))
    throw InputError(filename_ +
                     ": the numbers of 'subsection' and 'end' lines differ; every subsection "
                     "must be closed by 'end'");
  if (line > 0)
  {
    std::istringstream lines(text_);
    std::string content;
    for (unsigned int n = 0; n < line && std::getline(lines, content); ++n)
    {
    }
    throw InputError(at + ": cannot read the line '" + trim(content) +
                     "'; allowed: 'subsection NAME', 'set ENTRY = VALUE', 'end', comments after #");
  }
  throw InputError(filename_ + ": " + trim(text));
}

unsigned int ParameterFile::line_of(const std::string& p, const std::string& name) const
{
  const auto it = entry_line_.find({p, name});
  return it == entry_line_.end() ? 0 : it->second;
}

std::string ParameterFile::get(const std::string& name) const
{
  return handler_.get(name);
}

double ParameterFile::get_double(const std::string& name) const
{
  // As get_doubles: a number too small for a double is taken as the nearest
  // value (ParameterHandler::get_double would refuse what its pattern took).
  const double value = std::strtod(handler_.get(name).c_str(), nullptr);
  if (!std::isfinite(value))
    throw error(name, "value '" + handler_.get(name) + "' is not a finite number",
                "a finite number");
  return value;
}

long ParameterFile::get_integer(const std::string& name) const
{
  return handler_.get_integer(name);
}

bool ParameterFile::get_bool(const std::string& name) const
{
  return handler_.get_bool(name);
}

std::vector<double> ParameterFile::get_doubles(const std::string& name) const
{
  // The entry's pattern has accepted every number; strtod (unlike std::stod)
  // takes one too small for a double as the nearest value, as the pattern did.
  std::vector<double> values;
  for (const std::string& part : dealii::Utilities::split_string_list(get(name), ','))
  {
    values.push_back(std::strtod(part.c_str(), nullptr));
    if (!std::isfinite(values.back()))
      throw error(name, "'" + part + "' is not a finite number", "finite numbers");
  }
  return values;
}

Vec3 ParameterFile::get_vec3(const std::string& name) const
{
  const std::vector<double> v = get_doubles(name);
  if (v.size() != 3)
    throw error(name, "must be three numbers", "three numbers separated by commas");
  return Vec3(v[0], v[1], v[2]);
}

InputError ParameterFile::error(const std::string& name, const std::string& problem,
                                const std::string& allowed) const
{
  const unsigned int expanded = line_of(path(), name);
  const unsigned int line = expanded > 0 ? origin_[expanded - 1].second : 0;
  return InputError::at(expanded > 0 ? origin_[expanded - 1].first : filename_, line, path(), name,
                        line == 0 ? problem + " (default value)" : problem, allowed);
}

std::vector<std::string> ParameterFile::sections_in(const std::string& section) const
{
  std::vector<std::pair<unsigned int, std::string>> found;
  const std::string prefix = section + " / ";
  for (const auto& [path, line] : section_line_)
    if (path.rfind(prefix, 0) == 0 && path.find(" / ", prefix.size()) == std::string::npos)
      found.emplace_back(line, path.substr(prefix.size()));
  std::sort(found.begin(), found.end());
  std::vector<std::string> names;
  for (const auto& f : found)
    names.push_back(f.second);
  return names;
}

std::map<std::string, unsigned int> ParameterFile::lines() const
{
  std::map<std::string, unsigned int> lines;
  for (const auto& [section, line] : section_line_)
    lines.emplace(section, origin_[line - 1].second);
  for (const auto& [entry, line] : entry_line_)
    lines.emplace(entry.first + " / " + entry.second, origin_[line - 1].second);
  return lines;
}

std::string ParameterFile::file_of(const std::string& name) const
{
  const unsigned int line = line_of(path(), name);
  return line > 0 ? origin_[line - 1].first : filename_;
}

std::map<std::string, std::string> ParameterFile::line_files() const
{
  std::map<std::string, std::string> files;
  for (const auto& [section, line] : section_line_)
    if (origin_[line - 1].first != filename_)
      files.emplace(section, origin_[line - 1].first);
  for (const auto& [entry, line] : entry_line_)
    if (origin_[line - 1].first != filename_)
      files.emplace(entry.first + " / " + entry.second, origin_[line - 1].first);
  return files;
}

std::string ParameterFile::used_parameters() const
{
  std::ostringstream out;
  handler_.print_parameters(out, dealii::ParameterHandler::PRM);
  return out.str();
}

} // namespace talus
