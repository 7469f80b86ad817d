#include <talus/base/archive.h>
#include <talus/base/exceptions.h>

namespace talus
{

// ---- Reader ----------------------------------------------------------------

void CheckpointReader::tag(const char* name)
{
  std::string found;
  get(found);
  if (found != name)
    throw InputError(file_ + ": the checkpoint's section '" + found.substr(0, 40) +
                     "' is not the expected '" + name +
                     "' (written by another talus?); allowed: a checkpoint of this talus");
}

void CheckpointReader::get(std::string& s)
{
  std::uint64_t n = 0;
  get(n);
  if (n > bytes_.size() - at_)
    truncated();
  s.assign(bytes_.data() + at_, n);
  at_ += n;
}

void CheckpointReader::mismatch(const char* what, std::uint64_t found, std::uint64_t expected) const
{
  throw InputError(file_ + ": the checkpoint does not fit the model built from the parameter " +
                   "file (" + std::to_string(found) + " " + what + " in the checkpoint, " +
                   std::to_string(expected) +
                   " in the model); allowed: a checkpoint of this scene");
}

void CheckpointReader::truncated() const
{
  throw InputError(file_ + ": the checkpoint ends in the middle of its data; allowed: a "
                           "complete checkpoint written by talus");
}

} // namespace talus
