#pragma once

// Private to source/: wraps deal.II's ParameterHandler so that every error
// reaches the user as one InputError naming file, line, entry and what is
// allowed. Kept out of include/ so that talus headers stay free of deal.II.

#include <talus/base/exceptions.h>
#include <talus/geometry/plane.h>

#include <deal.II/base/parameter_handler.h>

#include <map>
#include <string>
#include <vector>

namespace talus
{

class ParameterFile
{
public:
  /// Reads the file's text (with the files it includes: 'include FILE',
  /// relative to the including file's folder) and notes where every
  /// subsection and entry is. A UTF-8 byte-order mark is skipped; lines may
  /// end in LF, CR LF or CR alone.
  explicit ParameterFile(const std::string& filename);

  /// Names of the top-level subsections the file uses, in order of first use.
  const std::vector<std::string>& sections_in_file() const { return sections_in_file_; }
  /// Names of the subsections the file opens directly inside `section`
  /// (a top-level one), in the order of their lines.
  std::vector<std::string> sections_in(const std::string& section) const;

  /// Enters/leaves a subsection for declarations and reads.
  void enter(const std::string& section);
  void leave();

  /// Declares an entry; `allowed` says in words what values are accepted.
  void declare(const std::string& name, const std::string& default_value,
               const dealii::Patterns::PatternBase& pattern, const std::string& allowed,
               const std::string& documentation);

  /// Parses the file; converts every deal.II parse error into an InputError.
  void parse();

  std::string get(const std::string& name) const;
  double get_double(const std::string& name) const;
  long get_integer(const std::string& name) const;
  bool get_bool(const std::string& name) const;
  Vec3 get_vec3(const std::string& name) const;
  /// Whether the file sets entry `name` of the current subsection.
  bool is_set(const std::string& name) const { return line_of(path(), name) > 0; }
  /// A list of numbers separated by commas (the pattern has checked them).
  std::vector<double> get_doubles(const std::string& name) const;

  /// An InputError about an entry of the current subsection, at its line in
  /// the file (or naming the default when the file does not set it).
  InputError error(const std::string& name, const std::string& problem,
                   const std::string& allowed) const;

  /// The parameters as used, in deal.II's .prm format.
  std::string used_parameters() const;

  const std::string& filename() const { return filename_; }
  /// The file that sets entry `name` of the current subsection: an included
  /// file, or the parameter file (also when the entry is not set). A path
  /// an entry names is relative to the folder of the file it is written in.
  std::string file_of(const std::string& name) const;

  /// Line of each subsection ("Joint set 1", first opening) and of each
  /// entry the file sets ("Joint set 1 / Spacing"), for messages about
  /// problems found after reading.
  std::map<std::string, unsigned int> lines() const;
  /// The included file of each key of lines() that is not in the file itself.
  std::map<std::string, std::string> line_files() const;

private:
  /// Appends `file` (and what it includes) to text_, one origin per line.
  void read_text(const std::string& file, std::vector<std::string>& open_files);
  /// "file:line" of a line of text_ (0: the parameter file itself).
  std::string where(unsigned int line) const;
  std::string path() const;
  unsigned int line_of(const std::string& path, const std::string& name) const;
  [[noreturn]] void rethrow(const dealii::ExceptionBase& e) const;

  std::string filename_;
  std::string text_; ///< the file with its includes in place, lines ending in '\n'
  /// (file, line) of each line of text_.
  std::vector<std::pair<std::string, unsigned int>> origin_;
  dealii::ParameterHandler handler_;
  std::vector<std::string> current_;
  std::vector<std::string> sections_in_file_;
  /// (subsection path, entry) -> line of its `set` statement.
  std::map<std::pair<std::string, std::string>, unsigned int> entry_line_;
  /// subsection path -> line where it is first opened.
  std::map<std::string, unsigned int> section_line_;
  /// line -> (subsection path, entry, value) for every `set` statement.
  std::map<unsigned int, std::vector<std::string>> line_entry_;
  /// subsection path -> entries declared there, with what they allow.
  std::map<std::string, std::vector<std::pair<std::string, std::string>>> declared_;
};

} // namespace talus
