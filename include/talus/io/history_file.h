#pragma once

#include <iostream>
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
  int digits_ = 12; ///< significant digits of each number (TALUS_HISTORY_DIGITS)
  unsigned int rows_ = 0;
  unsigned int rows_on_disk_ = 0;
  double last_write_ = 0.0;    ///< s, wall clock at the end of the last write
  double write_seconds_ = 0.0; ///< s, how long the last write took
};

/// Progress of a long run: step, model time, unbalanced-force ratio, rate
/// and the estimated time left. On a terminal, one line on standard error
/// rewritten in place at most every 2 s; otherwise (output to a log file)
/// a full line every `log_interval` seconds, so that a run in the
/// background is never silent. Standard error keeps it apart from results.
class ProgressLine
{
public:
  /// `log_interval` < 0: from the environment variable
  /// TALUS_PROGRESS_SECONDS, else 10 s; 0: no lines when not on a terminal.
  explicit ProgressLine(unsigned long total_steps, std::ostream& out = std::cerr,
                        double log_interval = -1.0);
  ~ProgressLine();

  /// Reports the state after step `step` (model time `time`, s; the
  /// unbalanced-force ratio `ratio`) if its interval has passed.
  void update(unsigned long step, double time, double ratio);

  /// Clears the line, so that what is printed next starts on a clean line.
  void finish();

  /// The text shown for the given state (separated out for testing).
  static std::string format(unsigned long step, unsigned long total, double time, double ratio,
                            double steps_per_second);

private:
  unsigned long total_;
  std::ostream& out_;
  double interval_;
  double start_;
  double last_ = 0.0;
  bool shown_ = false;
  bool terminal_ = false;
};

} // namespace talus
