#pragma once

namespace talus
{

/// How the data arrays of a VTU file are written: compressed binary (zlib
/// blocks, base64 inline, as VTK's vtkZLibDataCompressor reads them; the
/// default: small files, fast to write and read) or ASCII text (to read by
/// eye; floating-point values in their shortest form that reads back
/// exactly).
enum class VtuEncoding
{
  binary,
  ascii
};

} // namespace talus
