#include <talus/base/exceptions.h>
#include <talus/model/time_history.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace talus
{

namespace
{
constexpr double pi = 3.14159265358979323846;

/// The sample interval [time[k], time[k + 1]] that holds t (t inside the table).
std::size_t interval_of(const std::vector<double>& time, double t)
{
  const auto after = std::upper_bound(time.begin(), time.end(), t);
  const std::size_t k = static_cast<std::size_t>(after - time.begin());
  return std::min(k == 0 ? 0 : k - 1, time.size() - 2);
}
} // namespace

double TimeFunction::record_start() const
{
  return kind == Kind::table ? time.front() : start;
}

double TimeFunction::record_end() const
{
  return kind == Kind::table ? time.back() : end;
}

double TimeFunction::input(double t) const
{
  switch (kind)
  {
  case Kind::none:
    return 1.0;
  case Kind::table:
  {
    if (t <= time.front())
      return acceleration && t < time.front() ? 0.0 : value.front();
    if (t >= time.back())
      return acceleration && t > time.back() ? 0.0 : value.back();
    const std::size_t k = interval_of(time, t);
    const double w = (t - time[k]) / (time[k + 1] - time[k]);
    return (1.0 - w) * value[k] + w * value[k + 1];
  }
  case Kind::harmonic:
    if (t < start || t > end)
      return 0.0;
    return amplitude * std::sin(2.0 * pi * frequency * (t - start) + phase);
  case Kind::pulse:
    if (t < start || t > end)
      return 0.0;
    return amplitude * std::sin(pi * (t - start) / (end - start));
  }
  return 0.0;
}

double TimeFunction::integral(double t) const
{
  const double t0 = record_start(), t1 = record_end();
  if (t <= t0)
    return 0.0;
  const double tau = std::min(t, t1) - t0; // time into the record
  switch (kind)
  {
  case Kind::none:
    return tau;
  case Kind::table:
  {
    // Exact for the linear interpolation: the trapezoid sums at the samples,
    // a quadratic in between.
    if (t >= t1)
      return integral_at_sample_.back();
    const std::size_t k = interval_of(time, t);
    const double h = time[k + 1] - time[k], s = t - time[k];
    return integral_at_sample_[k] + value[k] * s + (value[k + 1] - value[k]) * s * s / (2.0 * h);
  }
  case Kind::harmonic:
  {
    const double omega = 2.0 * pi * frequency;
    return amplitude / omega * (std::cos(phase) - std::cos(omega * tau + phase));
  }
  case Kind::pulse:
  {
    const double duration = end - start;
    return amplitude * duration / pi * (1.0 - std::cos(pi * tau / duration));
  }
  }
  return 0.0;
}

double TimeFunction::scale(double t) const
{
  if (kind == Kind::none)
    return 1.0;
  if (!acceleration)
    return input(t);
  const double t0 = record_start();
  const double into = std::clamp(t, t0, std::max(t0, record_end())) - t0;
  return integral(t) - baseline * into;
}

void TimeFunction::integrate_acceleration(bool correct_baseline)
{
  acceleration = true;
  baseline = 0.0;
  if (kind == Kind::table)
  {
    integral_at_sample_.assign(time.size(), 0.0);
    for (std::size_t k = 1; k < time.size(); ++k)
      integral_at_sample_[k] =
          integral_at_sample_[k - 1] + 0.5 * (value[k - 1] + value[k]) * (time[k] - time[k - 1]);
  }
  if (correct_baseline && std::isfinite(record_end()) && record_end() > record_start())
    baseline = integral(record_end()) / (record_end() - record_start());
}

TimeFunction read_time_table(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
    throw InputError("cannot open the time table '" + path + "'");
  TimeFunction f;
  f.kind = TimeFunction::Kind::table;
  std::string line;
  unsigned int number = 0;
  bool header_allowed = true;
  const auto fail = [&](const std::string& problem)
  { return InputError("'" + path + "' line " + std::to_string(number) + ": " + problem); };
  while (std::getline(in, line))
  {
    ++number;
    if (!line.empty() && line.back() == '\r')
      line.pop_back();
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#')
      continue;
    std::vector<std::string> fields;
    std::stringstream s(line);
    for (std::string field; std::getline(s, field, ',');)
      fields.push_back(field);
    if (line.back() == ',')
      fields.push_back("");
    double numbers[2] = {0.0, 0.0};
    bool numeric = fields.size() == 2;
    std::string bad;
    for (std::size_t c = 0; c < fields.size() && c < 2; ++c)
    {
      const char* text = fields[c].c_str();
      char* stop = nullptr;
      numbers[c] = std::strtod(text, &stop);
      while (stop != nullptr && std::isspace(static_cast<unsigned char>(*stop)))
        ++stop;
      if (stop == text || *stop != '\0' || !std::isfinite(numbers[c]) ||
          fields[c].find_first_not_of(" \t") == std::string::npos)
      {
        numeric = false;
        if (bad.empty())
        {
          bad = fields[c];
          bad.erase(0, bad.find_first_not_of(" \t"));
          bad.erase(bad.find_last_not_of(" \t") + 1);
        }
      }
    }
    if (!numeric && header_allowed && f.time.empty())
    {
      header_allowed = false; // one header line
      continue;
    }
    header_allowed = false;
    if (fields.size() != 2)
      throw fail("has " + std::to_string(fields.size()) +
                 (fields.size() == 1 ? " field" : " fields") + " where two are needed");
    if (!numeric)
      throw fail("'" + bad + "' is not a finite number");
    if (!f.time.empty() && numbers[0] <= f.time.back())
      throw fail("time " + talus::number(numbers[0]) + " s does not follow the time before it (" +
                 talus::number(f.time.back()) + " s)");
    f.time.push_back(numbers[0]);
    f.value.push_back(numbers[1]);
  }
  if (f.time.size() < 2)
    throw InputError("'" + path + "' holds " + std::to_string(f.time.size()) +
                     (f.time.size() == 1 ? " sample" : " samples") +
                     " where at least two are needed");
  return f;
}

} // namespace talus
