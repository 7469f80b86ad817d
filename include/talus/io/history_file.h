#pragma once

#include <string>
#include <vector>

namespace talus
{

class CheckpointReader;
class CheckpointWriter;

/// A history: one CSV row per recorded step, one column per quantity, the
/// names (with units) in the header row. The file on disk is always whole:
/// it is rewritten under a temporary name and renamed into place (never
/// appended to), at most every `flush_every` rows and no more often than
/// about once a second (and never taking more than a tenth of the run), so a
/// killed run leaves every row up to the last rewrite and no partial line.
class HistoryFile
{
public:
  /// Writes the header row at once: a run stopped later leaves a valid file.
  /// A restart (`write_now` false) leaves the file alone: a checkpoint that
  /// is refused must not change it, and restoring one rewrites it.
  HistoryFile(const std::string& path, const std::vector<std::string>& columns,
              unsigned int flush_every = 100, bool write_now = true);
  /// Writes the rows not yet on disk.
  ~HistoryFile();
  HistoryFile(const HistoryFile&) = delete;
  HistoryFile& operator=(const HistoryFile&) = delete;

  /// Appends one row; `values` must match the columns in number. A value
  /// that is not finite (a run that overflowed) throws DivergenceError
  /// naming its column, and the row is not kept.
  void record(const std::vector<double>& values);

  /// Writes every row recorded so far to disk now (e.g. with a checkpoint).
  void flush();

  unsigned int n_rows() const { return rows_; }

  /// Checkpoints: the file's text so far; loading takes it (no row after the
  /// checkpoint's step, none twice) and appends from there. The file is
  /// rewritten by rewrite(), once the whole checkpoint has been read.
  void save_state(CheckpointWriter& out);
  void load_state(CheckpointReader& in);
  /// Writes the whole file now.
  void rewrite();

private:
  std::string path_;
  std::string text_; ///< the whole file: header and every row
  std::vector<std::string> columns_;
  std::size_t n_columns_;
  unsigned int flush_every_;
  unsigned int rows_ = 0;
  unsigned int rows_on_disk_ = 0;
  double last_write_ = 0.0;    ///< s, wall clock at the end of the last write
  double write_seconds_ = 0.0; ///< s, how long the last write took
};

/// A one-line progress report for long runs: step, time, rate and the
/// estimated time left, rewritten in place at most once per `interval`
/// seconds, on standard error so that it never mixes with results.
class ProgressLine
{
public:
  explicit ProgressLine(unsigned long total_steps, double interval = 2.0);
  ~ProgressLine();

  /// Reports step `step` at model time `time` (s) if `interval` has passed.
  /// Shown only when standard error is a terminal, so logs stay clean.
  void update(unsigned long step, double time);

  /// Clears the line, so that what is printed next starts on a clean line.
  void finish();

  /// The text shown for the given state (separated out for testing).
  static std::string format(unsigned long step, unsigned long total, double time,
                            double steps_per_second);

private:
  unsigned long total_;
  double interval_;
  double start_;
  double last_ = 0.0;
  bool shown_ = false;
  bool terminal_ = false;
};

} // namespace talus
