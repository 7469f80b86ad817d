#pragma once

// The archive a solver saves its state into and loads it from: plain
// values, strings and vectors in a byte buffer, in sections with tags.
// io/checkpoint puts the buffer in a file (with its header, fingerprints
// and checksum); the solvers know only this.

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace talus
{

/// Serialises values into a byte buffer: plain values as their bytes,
/// vectors and strings with their length first.
class CheckpointWriter
{
public:
  /// Starts a section: its tag is checked on reading, so that a file whose
  /// layout differs is refused instead of misread.
  void tag(const char* name) { put(std::string(name)); }

  template <typename T>
  void put(const T& value)
  {
    static_assert(std::is_trivially_copyable<T>::value, "plain values only");
    append(&value, sizeof(T));
  }
  void put(const std::string& s)
  {
    put(static_cast<std::uint64_t>(s.size()));
    append(s.data(), s.size());
  }
  /// Vectors of plain values, or of fixed-size Eigen objects (their
  /// coefficients, contiguous).
  template <typename T>
  void put(const std::vector<T>& v)
  {
    put(static_cast<std::uint64_t>(v.size()));
    append(v.data(), v.size() * sizeof(T));
  }

  const std::string& bytes() const { return bytes_; }

private:
  void append(const void* data, std::size_t size)
  {
    bytes_.append(static_cast<const char*>(data), size);
  }
  std::string bytes_;
};

/// Reads what CheckpointWriter wrote, throwing InputError naming the file
/// when the data ends early or does not fit the model.
class CheckpointReader
{
public:
  CheckpointReader(std::string bytes, std::string file)
      : bytes_(std::move(bytes)), file_(std::move(file))
  {
  }

  void tag(const char* name);

  template <typename T>
  void get(T& value)
  {
    static_assert(std::is_trivially_copyable<T>::value, "plain values only");
    take(&value, sizeof(T));
  }
  void get(std::string& s);
  /// A vector; with `expected` (not npos), its length must be that (the
  /// number of blocks, gridpoints, ... of the model rebuilt from the scene).
  template <typename T>
  void get(std::vector<T>& v, std::size_t expected = npos, const char* what = "")
  {
    std::uint64_t n = 0;
    get(n);
    if (expected != npos && n != expected)
      mismatch(what, n, expected);
    if (n > (bytes_.size() - at_) / std::max<std::size_t>(1, sizeof(T)))
      truncated();
    v.resize(n);
    take(v.data(), n * sizeof(T));
  }

  /// Throws the "does not match the scene" error.
  [[noreturn]] void mismatch(const char* what, std::uint64_t found, std::uint64_t expected) const;
  [[noreturn]] void truncated() const;
  const std::string& file() const { return file_; }
  bool at_end() const { return at_ == bytes_.size(); }

  static constexpr std::size_t npos = static_cast<std::size_t>(-1);

private:
  void take(void* data, std::size_t size)
  {
    if (size > bytes_.size() - at_)
      truncated();
    if (size > 0)
      std::memcpy(data, bytes_.data() + at_, size);
    at_ += size;
  }
  std::string bytes_;
  std::string file_;
  std::size_t at_ = 0;
};

} // namespace talus
