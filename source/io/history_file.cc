#include <talus/base/exceptions.h>
#include <talus/io/history_file.h>

#include <unistd.h>
#include <cstdio>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <algorithm>

namespace talus
{

HistoryFile::HistoryFile(const std::string& path, const std::vector<std::string>& columns,
                         unsigned int flush_every)
    : path_(path), out_(path), n_columns_(columns.size()), flush_every_(flush_every)
{
  if (!out_)
    throw InputError(path + ": cannot create the history file (is its folder writable?)");
  out_.precision(12);
  for (std::size_t c = 0; c < columns.size(); ++c)
    out_ << (c ? "," : "") << columns[c];
  out_ << '\n';
}

void HistoryFile::record(const std::vector<double>& values)
{
  if (values.size() != n_columns_)
    throw std::logic_error(path_ + ": a history row has " + std::to_string(values.size()) +
                           " values for " + std::to_string(n_columns_) + " columns");
  for (std::size_t c = 0; c < values.size(); ++c)
    out_ << (c ? "," : "") << values[c];
  out_ << '\n';
  if (++rows_ % flush_every_ == 0)
    out_.flush();
}

namespace
{
double wall_seconds()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}
} // namespace

ProgressLine::ProgressLine(unsigned long total_steps, double interval)
    : total_(total_steps), interval_(interval), start_(wall_seconds())
{
  last_ = start_;
  terminal_ = isatty(fileno(stderr)) != 0;
}

ProgressLine::~ProgressLine() { finish(); }

void ProgressLine::finish()
{
  if (shown_)
    std::cerr << '\r' << std::string(79, ' ') << '\r' << std::flush;
  shown_ = false;
}

std::string ProgressLine::format(unsigned long step, unsigned long total, double time,
                                 double steps_per_second)
{
  char line[160];
  const double left = steps_per_second > 0.0 && total > step
                          ? static_cast<double>(total - step) / steps_per_second
                          : 0.0;
  std::snprintf(line, sizeof line, "step %lu/%lu  t = %.4g s  %.3g steps/s  %.0f s left", step,
                total, time, steps_per_second, left);
  return line;
}

void ProgressLine::update(unsigned long step, double time)
{
  if (!terminal_)
    return;
  const double now = wall_seconds();
  if (now - last_ < interval_)
    return;
  last_ = now;
  shown_ = true;
  std::cerr << '\r' << format(step, total_, time, step / std::max(now - start_, 1e-9))
            << "   " << std::flush;
}

} // namespace talus
