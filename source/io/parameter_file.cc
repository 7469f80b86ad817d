#include "parameter_file.h"

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cerrno>
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

ParameterFile::ParameterFile(const std::string& filename) : filename_(filename)
{
  std::error_code ec;
  if (!std::filesystem::is_regular_file(filename, ec))
    throw InputError(filename + ": " +
                     (std::filesystem::exists(filename, ec) ? "not a file"
                                                            : "no such parameter file") +
                     "; allowed: a readable parameter file (.prm)");
  std::ifstream in(filename, std::ios::binary);
  if (!in)
    throw InputError(filename + ": cannot open the parameter file (" + std::strerror(errno) +
                     "); allowed: a readable parameter file (.prm)");
  std::stringstream buffer;
  buffer << in.rdbuf();
  text_ = buffer.str();
  if (in.bad())
    throw InputError(filename + ": reading the parameter file failed");

  // A lenient first pass that only records where things are; the real parse
  // (and its error reporting) is ParameterHandler's.
  std::istringstream lines(text_);
  std::string line;
  std::vector<std::string> stack;
  bool any_statement = false;
  for (unsigned int number = 1; std::getline(lines, line); ++number)
  {
    for (const char c : line)
      if ((static_cast<unsigned char>(c) < 32 && c != '\t' && c != '\r') || c == 127)
      {
        char byte[8];
        std::snprintf(byte, sizeof byte, "0x%02x", static_cast<unsigned char>(c));
        throw InputError(filename + ":" + std::to_string(number) +
                         ": the line holds a control character (byte " + byte +
                         "), so this is not a text file; allowed: a parameter file of text lines");
      }
    const auto hash = line.find('#');
    const std::string code = trim(hash == std::string::npos ? line : line.substr(0, hash));
    if (code.rfind("subsection ", 0) == 0 || code.rfind("subsection\t", 0) == 0)
    {
      stack.push_back(collapse(code.substr(10)));
      section_line_.emplace(join_path(stack), number);
      if (stack.size() == 1 &&
          std::find(sections_in_file_.begin(), sections_in_file_.end(), stack[0]) ==
              sections_in_file_.end())
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
      entry_line_.emplace(std::make_pair(join_path(stack), name), number);
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
  const std::string where = filename_ + (line > 0 ? ":" + std::to_string(line) : "");

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
    throw InputError::at(filename_, line, entry[0], entry[1], "value '" + entry[2] + "' is invalid",
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
    throw InputError::at(filename_, line, section, m[1], "no such entry",
                         names.empty() ? "" : "entries " + names);
  }
  if (std::regex_search(text, m, std::regex("no such subsection to be entered: ([^\n]*)")))
  {
    std::string names;
    for (const auto& d : declared_)
      if (!d.first.empty() && d.first.find(" / ") == std::string::npos)
        names += (names.empty() ? "" : ", ") + d.first;
    throw InputError(where + ": unknown subsection '" + trim(m[1]) + "'; allowed: " + names +
                     " (numbered ones: 'Joint set N', 'Joint N', 'Excavation N', 'Group N', 'Load N', 'Boundary N')");
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
    throw InputError(where + ": cannot read the line '" + trim(content) +
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
  return std::strtod(handler_.get(name).c_str(), nullptr);
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
    values.push_back(std::strtod(part.c_str(), nullptr));
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
  const unsigned int line = line_of(path(), name);
  return InputError::at(filename_, line, path(), name,
                        line == 0 ? problem + " (default value)" : problem, allowed);
}

std::map<std::string, unsigned int> ParameterFile::lines() const
{
  std::map<std::string, unsigned int> lines = section_line_;
  for (const auto& [where, line] : entry_line_)
    lines.emplace(where.first + " / " + where.second, line);
  return lines;
}

std::string ParameterFile::used_parameters() const
{
  std::ostringstream out;
  handler_.print_parameters(out, dealii::ParameterHandler::PRM);
  return out.str();
}

} // namespace talus
