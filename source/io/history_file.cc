#include <talus/base/exceptions.h>
#include <talus/io/file_output.h>
#include <talus/io/history_file.h>
#include <talus/solver/energy_account.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <stdexcept>

namespace talus
{

namespace
{
double wall_seconds()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
} // namespace

HistoryFile::HistoryFile(const std::string& path, const std::vector<std::string>& columns,
                         unsigned int flush_every, bool write_now)
    : path_(path), columns_(columns), n_columns_(columns.size()),
      flush_every_(std::max(flush_every, 1u))
{
  // 12 significant digits; TALUS_HISTORY_DIGITS=17 writes every double
  // exactly (tests/parallel compares runs on ranks to the last bit).
  if (const char* text = std::getenv("TALUS_HISTORY_DIGITS"); text != nullptr && *text != '\0')
  {
    char* end = nullptr;
    const long given = std::strtol(text, &end, 10);
    if (*end == '\0' && given >= 1 && given <= 17)
      digits_ = static_cast<int>(given);
  }
  for (std::size_t c = 0; c < columns.size(); ++c)
    text_ += (c ? "," : "") + columns[c];
  text_ += '\n';
  if (write_now)
    write_file_atomically(path_, [&](std::ostream& out) { out << text_; });
  last_write_ = wall_seconds();
}

HistoryFile::~HistoryFile()
{
  try
  {
    flush();
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "talus: %s\n", e.what()); // a destructor must not throw
  }
}

void HistoryFile::record(const std::vector<double>& values)
{
  if (values.size() != n_columns_)
    throw std::logic_error(path_ + ": a history row has " + std::to_string(values.size()) +
                           " values for " + std::to_string(n_columns_) + " columns");
  for (std::size_t c = 0; c < values.size(); ++c)
    if (!std::isfinite(values[c]))
      throw DivergenceError(
          "the history value '" + columns_[c] + "' is " +
          (std::isnan(values[c]) ? std::string("NaN")
           : values[c] > 0       ? "+inf"
                                 : "-inf") +
          (values.empty() ? std::string() : " at step " + talus::number(values[0])) +
          ": the run has left the range of double precision; likely cause: a gravity, load, "
          "force rate, pressure or velocity far beyond what the model can carry (see the "
          "entries of 'Solver', 'Load N' and 'Boundary N')");
  char number[32];
  for (std::size_t c = 0; c < values.size(); ++c)
  {
    std::snprintf(number, sizeof number, "%.*g", digits_, values[c]);
    text_ += (c ? "," : "");
    text_ += number;
  }
  text_ += '\n';
  ++rows_;
  // Rewriting the whole file costs time in its length: wait at least ten
  // times as long as the last write took, so that it stays a small share.
  if (rows_ - rows_on_disk_ >= flush_every_ &&
      wall_seconds() - last_write_ >= std::max(1.0, 10.0 * write_seconds_))
    flush();
}

void HistoryFile::rewrite()
{
  write_file_atomically(path_, [&](std::ostream& out) { out << text_; });
  rows_on_disk_ = rows_;
}

void HistoryFile::flush()
{
  if (rows_on_disk_ == rows_)
    return;
  const double start = wall_seconds();
  write_file_atomically(path_, [&](std::ostream& out) { out << text_; });
  last_write_ = wall_seconds();
  write_seconds_ = last_write_ - start;
  rows_on_disk_ = rows_;
}

ProgressLine::ProgressLine(unsigned long total_steps, std::ostream& out, double log_interval)
    : total_(total_steps), out_(out), start_(wall_seconds())
{
  last_ = start_;
  terminal_ = &out == &std::cerr && isatty(fileno(stderr)) != 0;
  if (terminal_)
    interval_ = 2.0;
  else if (log_interval >= 0.0)
    interval_ = log_interval;
  else
  {
    const char* text = std::getenv("TALUS_PROGRESS_SECONDS");
    char* end = nullptr;
    const double given = text != nullptr ? std::strtod(text, &end) : -1.0;
    interval_ = text != nullptr && end != text && *end == '\0' && given >= 0.0 ? given : 10.0;
  }
}

ProgressLine::~ProgressLine()
{
  finish();
}

void ProgressLine::finish()
{
  if (shown_)
    out_ << '\r' << std::string(100, ' ') << '\r' << std::flush;
  shown_ = false;
}

std::string ProgressLine::format(unsigned long step, unsigned long total, double time, double ratio,
                                 double steps_per_second)
{
  char line[200];
  const double left = steps_per_second > 0.0 && total > step
                          ? static_cast<double>(total - step) / steps_per_second
                          : 0.0;
  std::snprintf(line, sizeof line,
                "step %lu/%lu  t = %.4g s  ratio %.3g  %.3g steps/s  %.0f s left", step, total,
                time, ratio, steps_per_second, left);
  return line;
}

void ProgressLine::update(unsigned long step, double time, double ratio)
{
  if (interval_ <= 0.0)
    return;
  const double now = wall_seconds();
  if (now - last_ < interval_)
    return;
  last_ = now;
  const std::string text = format(step, total_, time, ratio, step / std::max(now - start_, 1e-9));
  if (terminal_)
  {
    shown_ = true;
    out_ << '\r' << text << "   " << std::flush;
  }
  else
    out_ << "talus: " << text << std::endl;
}

} // namespace talus
