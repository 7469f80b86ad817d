#pragma once

#include <stdexcept>
#include <string>

namespace talus
{

/// Bad user input: a parameter file entry, a block file, a missing file.
/// The message is complete by itself (file, line, entry, what is wrong, what is
/// allowed); `main` prints it once and exits with a non-zero code.
class InputError : public std::runtime_error
{
public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}

  /// Formats the project's one shape of input message:
  /// "<file>:<line>: entry '<entry>' in subsection '<section>': <problem>; allowed: <allowed>"
  static InputError at(const std::string& file, unsigned int line, const std::string& section,
                       const std::string& entry, const std::string& problem,
                       const std::string& allowed);
};

/// A number as messages show it: %g, six significant digits, no padding.
std::string number(double x);

/// A geometric object that cannot be used: an open or non-convex polyhedron,
/// a degenerate face. Carries a message naming what failed and where.
class GeometryError : public std::runtime_error
{
public:
  explicit GeometryError(const std::string& message) : std::runtime_error(message) {}
};

/// A numerical solve that cannot be done (a singular system, inconsistent
/// arrays) or did not converge. The message says which and by how much.
class SolverError : public std::runtime_error
{
public:
  explicit SolverError(const std::string& message) : std::runtime_error(message) {}
};

} // namespace talus
