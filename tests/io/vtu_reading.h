#pragma once

// Reads back the data arrays of a VTU file as talus writes it, with a
// decoder of its own (not the writer's): ASCII text, or inline binary with
// UInt64 headers compressed by vtkZLibDataCompressor's layout: base64 of
// the header [blocks, block size, last block size (0: full), compressed
// size of each block], then base64 of the compressed blocks one after the
// other. Every header figure is checked against the data found.

#include <zlib.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace vtu_reading
{

struct Array
{
  std::string type, name, format;
  unsigned int components = 1;
  std::vector<double> values;
  std::uint64_t blocks = 0, block_size = 0, last_block_size = 0;
  std::string problem; ///< empty when the encoding is consistent
};

inline std::string read_text(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

inline std::string attribute(const std::string& tag, const std::string& key)
{
  const std::size_t at = tag.find(" " + key + "=\"");
  if (at == std::string::npos)
    return "";
  const std::size_t start = at + key.size() + 3;
  return tag.substr(start, tag.find('"', start) - start);
}

/// Base64 to bytes; `ok` false on a character outside the alphabet or
/// padding in the middle.
inline std::string base64_decode(const std::string& text, bool& ok)
{
  static const std::string digits =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string bytes;
  unsigned int buffer = 0, bits = 0;
  bool padded = false;
  for (char c : text)
  {
    if (c == '=')
    {
      padded = true;
      continue;
    }
    const std::size_t d = digits.find(c);
    if (d == std::string::npos || padded)
    {
      ok = false;
      return bytes;
    }
    buffer = (buffer << 6) | static_cast<unsigned int>(d);
    bits += 6;
    if (bits >= 8)
    {
      bits -= 8;
      bytes.push_back(static_cast<char>((buffer >> bits) & 0xff));
    }
  }
  ok = text.size() % 4 == 0;
  return bytes;
}

inline std::size_t type_size(const std::string& type)
{
  if (type == "Float64" || type == "Int64" || type == "UInt64")
    return 8;
  if (type == "Float32" || type == "Int32" || type == "UInt32")
    return 4;
  return 1; // UInt8
}

inline double value_at(const std::string& type, const char* p)
{
  if (type == "Float64")
  {
    double v;
    std::memcpy(&v, p, 8);
    return v;
  }
  if (type == "Float32")
  {
    float v;
    std::memcpy(&v, p, 4);
    return v;
  }
  if (type == "Int64")
  {
    std::int64_t v;
    std::memcpy(&v, p, 8);
    return static_cast<double>(v);
  }
  if (type == "Int32")
  {
    std::int32_t v;
    std::memcpy(&v, p, 4);
    return v;
  }
  return static_cast<unsigned char>(*p);
}

inline void decode_binary(const std::string& text, Array& a)
{
  std::string trimmed;
  for (char c : text)
    if (c != ' ' && c != '\n')
      trimmed.push_back(c);
  bool ok = true;
  // The first three words are 24 bytes: 32 characters with no padding.
  const std::string start = base64_decode(trimmed.substr(0, 32), ok);
  if (!ok || start.size() != 24)
  {
    a.problem = "header too short";
    return;
  }
  std::uint64_t word[3];
  std::memcpy(word, start.data(), 24);
  a.blocks = word[0];
  a.block_size = word[1];
  a.last_block_size = word[2];
  const std::size_t header_chars = 4 * ((8 * (3 + a.blocks) + 2) / 3);
  const std::string header = base64_decode(trimmed.substr(0, header_chars), ok);
  const std::string packed = base64_decode(trimmed.substr(header_chars), ok);
  if (!ok || header.size() != 8 * (3 + a.blocks))
  {
    a.problem = "bad base64";
    return;
  }
  std::size_t at = 0;
  std::string raw;
  for (std::uint64_t b = 0; b < a.blocks; ++b)
  {
    std::uint64_t size;
    std::memcpy(&size, header.data() + 8 * (3 + b), 8);
    const bool last = b + 1 == a.blocks;
    const std::uint64_t expected =
        last && a.last_block_size != 0 ? a.last_block_size : a.block_size;
    std::string block(expected, '\0');
    uLongf length = expected;
    if (at + size > packed.size() ||
        uncompress(reinterpret_cast<Bytef*>(&block[0]), &length,
                   reinterpret_cast<const Bytef*>(packed.data() + at), size) != Z_OK ||
        length != expected)
    {
      a.problem = "block " + std::to_string(b) + " does not inflate to its size";
      return;
    }
    at += size;
    raw += block;
  }
  if (at != packed.size())
    a.problem = "data longer than the blocks";
  const std::size_t size = type_size(a.type);
  if (raw.size() % size != 0)
    a.problem = "partial value";
  for (std::size_t i = 0; i + size <= raw.size(); i += size)
    a.values.push_back(value_at(a.type, raw.data() + i));
}

inline void decode_ascii(const std::string& text, Array& a)
{
  std::istringstream in(text);
  for (std::string word; in >> word;)
  {
    char* end = nullptr;
    const double v = a.type == "Float32"   ? double(std::strtof(word.c_str(), &end))
                     : a.type == "Float64" ? std::strtod(word.c_str(), &end)
                                           : double(std::strtoll(word.c_str(), &end, 10));
    if (*end != '\0')
      a.problem = "not a number: " + word;
    a.values.push_back(v);
  }
}

/// Every DataArray of the file, in order.
inline std::vector<Array> read_arrays(const std::string& file)
{
  std::vector<Array> arrays;
  for (std::size_t at = file.find("<DataArray"); at != std::string::npos;
       at = file.find("<DataArray", at + 1))
  {
    const std::size_t tag_end = file.find('>', at);
    const std::string tag = file.substr(at, tag_end - at);
    Array a;
    a.type = attribute(tag, "type");
    a.name = attribute(tag, "Name");
    a.format = attribute(tag, "format");
    const std::string components = attribute(tag, "NumberOfComponents");
    a.components = components.empty() ? 1 : std::stoul(components);
    const std::size_t end = file.find("</DataArray>", tag_end);
    const std::string text = file.substr(tag_end + 1, end - tag_end - 1);
    if (a.format == "binary")
      decode_binary(text, a);
    else
      decode_ascii(text, a);
    arrays.push_back(a);
  }
  return arrays;
}

/// The array called `name` (the first one), or an empty one.
inline Array find(const std::vector<Array>& arrays, const std::string& name)
{
  for (const Array& a : arrays)
    if (a.name == name)
      return a;
  return Array{};
}

} // namespace vtu_reading
