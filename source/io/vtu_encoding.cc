#include <talus/io/vtu_encoding.h>

#include <zlib.h>

#include <charconv>
#include <stdexcept>

namespace talus
{

void write_vtu_file_start(std::ostream& out, VtuEncoding encoding)
{
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\""
      << (encoding == VtuEncoding::binary ? " compressor=\"vtkZLibDataCompressor\"" : "") << ">\n";
}

void append_base64(const unsigned char* bytes, std::size_t size, std::string& text)
{
  static constexpr char digit[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const std::size_t start = text.size();
  text.resize(start + 4 * ((size + 2) / 3));
  char* to = &text[start];
  std::size_t i = 0;
  for (; i + 3 <= size; i += 3, to += 4)
  {
    const std::uint32_t word = (std::uint32_t(bytes[i]) << 16) |
                               (std::uint32_t(bytes[i + 1]) << 8) | std::uint32_t(bytes[i + 2]);
    to[0] = digit[word >> 18];
    to[1] = digit[(word >> 12) & 63];
    to[2] = digit[(word >> 6) & 63];
    to[3] = digit[word & 63];
  }
  if (i < size) // one or two bytes left: padded with '='
  {
    const std::uint32_t word =
        (std::uint32_t(bytes[i]) << 16) | (i + 1 < size ? std::uint32_t(bytes[i + 1]) << 8 : 0);
    to[0] = digit[word >> 18];
    to[1] = digit[(word >> 12) & 63];
    to[2] = i + 1 < size ? digit[(word >> 6) & 63] : '=';
    to[3] = '=';
  }
}

/// One deflate stream for all blocks of an array (reset between blocks,
/// each block a zlib stream of its own as VTK reads them).
struct VtuArrayEncoder::Deflater
{
  z_stream stream{};
  /// Integers (connectivity, offsets, ids) repeat in patterns that zlib's
  /// fastest matching shrinks 5 to 20 times. Floating-point values rarely
  /// repeat: Huffman coding alone takes nearly as much off them (their
  /// exponent and leading bytes) at half the cost, which keeps a zone frame
  /// above a million zones per second (benchmark_vtu_write).
  explicit Deflater(bool floating_point)
  {
    if (deflateInit2(&stream, Z_BEST_SPEED, Z_DEFLATED, 15, 8,
                     floating_point ? Z_HUFFMAN_ONLY : Z_DEFAULT_STRATEGY) != Z_OK)
      throw std::runtime_error("VTU output: zlib cannot start");
  }
  ~Deflater() { deflateEnd(&stream); }
};

VtuArrayEncoder::VtuArrayEncoder(std::ostream& out, VtuEncoding encoding, const char* type,
                                 const std::string& name, unsigned int components,
                                 std::size_t block_bytes)
    : out_(out), encoding_(encoding)
{
  out_ << "        <DataArray type=\"" << type << "\" Name=\"" << name << "\" NumberOfComponents=\""
       << components << "\" format=\"" << (encoding == VtuEncoding::binary ? "binary" : "ascii")
       << "\">\n";
  if (encoding == VtuEncoding::binary)
  {
    header_ = {0, block_bytes, 0};
    deflater_ = std::make_unique<Deflater>(type[0] == 'F'); // Float32, Float64
  }
}

VtuArrayEncoder::~VtuArrayEncoder() = default;

void VtuArrayEncoder::add_block(const void* data, std::size_t bytes)
{
  z_stream& z = deflater_->stream;
  if (deflateReset(&z) != Z_OK)
    throw std::runtime_error("VTU output: zlib failed");
  const std::size_t start = packed_.size();
  packed_.resize(start + deflateBound(&z, bytes));
  z.next_in = static_cast<Bytef*>(const_cast<void*>(data));
  z.avail_in = static_cast<uInt>(bytes);
  z.next_out = reinterpret_cast<Bytef*>(&packed_[start]);
  z.avail_out = static_cast<uInt>(packed_.size() - start);
  if (deflate(&z, Z_FINISH) != Z_STREAM_END)
    throw std::runtime_error("VTU output: zlib failed");
  packed_.resize(start + z.total_out);
  ++header_[0];
  header_.push_back(z.total_out);
  // The last block's size; 0 when it is a full one (VTK's convention).
  header_[2] = bytes == header_[1] ? 0 : bytes;
}

void VtuArrayEncoder::append_text(double value)
{
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, value).ptr;
  text_.append(buffer, end);
  text_.push_back(++column_ % 12 == 0 ? '\n' : ' ');
}

void VtuArrayEncoder::append_text(float value)
{
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, value).ptr;
  text_.append(buffer, end);
  text_.push_back(++column_ % 12 == 0 ? '\n' : ' ');
}

void VtuArrayEncoder::append_text(std::int64_t value)
{
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, value).ptr;
  text_.append(buffer, end);
  text_.push_back(++column_ % 12 == 0 ? '\n' : ' ');
}

void VtuArrayEncoder::flush_text()
{
  out_.write(text_.data(), static_cast<std::streamsize>(text_.size()));
  text_.clear();
}

void VtuArrayEncoder::finish()
{
  if (encoding_ == VtuEncoding::binary)
  {
    // The header, then the blocks, each base64 on its own (VTK reads the
    // header first to find the blocks).
    append_base64(reinterpret_cast<const unsigned char*>(header_.data()),
                  header_.size() * sizeof(std::uint64_t), text_);
    flush_text();
    constexpr std::size_t piece = 3 * (1 << 14); // whole groups of 3 bytes
    const auto* bytes = reinterpret_cast<const unsigned char*>(packed_.data());
    for (std::size_t at = 0; at < packed_.size(); at += piece)
    {
      append_base64(bytes + at, std::min(piece, packed_.size() - at), text_);
      flush_text();
    }
    std::string().swap(packed_);
  }
  else
    flush_text();
  out_ << "\n        </DataArray>\n";
}

} // namespace talus
