#pragma once

#include <fstream>
#include <string>
#include <vector>

namespace talus
{

class CheckpointReader;
class CheckpointWriter;

/// A history: one CSV row per recorded step, one column per quantity, the
/// names (with units) in the header row. Rows are flushed every
/// `flush_every` records so that a long run can be watched while it goes.
class HistoryFile
{
public:
  HistoryFile(const std::string& path, const std::vector<std::string>& columns,
              unsigned int flush_every = 100);

  /// Appends one row; `values` must match the columns in number.
  void record(const std::vector<double>& values);

  unsigned int n_rows() const { return rows_; }

  /// Checkpoints: the file's text so far; loading rewrites the file with it
  /// (no row after the checkpoint's step, none twice) and appends from there.
  void save_state(CheckpointWriter& out);
  void load_state(CheckpointReader& in);

private:
  std::string path_;
  std::ofstream out_;
  std::size_t n_columns_;
  unsigned int flush_every_;
  unsigned int rows_ = 0;
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
