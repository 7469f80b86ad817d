#include "time_function_reader.h"

#include <talus/base/exceptions.h>

#include <cmath>
#include <filesystem>

namespace talus
{

namespace
{
namespace P = dealii::Patterns;
constexpr double pi = 3.14159265358979323846;
} // namespace

void declare_time_function(ParameterFile& prm, const std::string& what)
{
  prm.declare("Time function", "none", P::Selection("none|table|harmonic|pulse"),
              "none, table, harmonic or pulse",
              "How " + what +
                  " varies in model time: none (constant), table ('Time table'), harmonic "
                  "('Amplitude' sin(2 pi 'Frequency' (t - 'Start time') + 'Phase') from 'Start "
                  "time' to 'End time of motion') or pulse (a half sine 'Amplitude' sin(pi (t - "
                  "'Start time') / 'Pulse duration')); " +
                  what + " is multiplied by f(t), or by its integral for 'Input = acceleration'.");
  prm.declare("Time table", "", P::Anything(),
              "a CSV file of lines 'time, value' (relative to the parameter file)",
              "table: the samples of f, linearly interpolated; before the first time the first "
              "value, after the last the last value (acceleration: 0).");
  prm.declare("Input", "value", P::Selection("value|acceleration"), "value or acceleration",
              "value: " + what +
                  " times f(t); acceleration: f is an acceleration (m/s^2) and the velocity is "
                  "'Velocity' times its integral.");
  prm.declare("Baseline correction", "false", P::Bool(), "true or false",
              "acceleration: take the constant acceleration v(T) / (T - T0) off over the record "
              "[T0, T], so that the integrated velocity ends at 0 and the base does not drift.");
  prm.declare("Amplitude", "1", P::Double(), "a number", "harmonic and pulse: amplitude of f.");
  prm.declare("Frequency", "1", P::Double(), "a number > 0 (Hz)", "harmonic: frequency (Hz).");
  prm.declare("Phase", "0", P::Double(), "a number (degrees)", "harmonic: phase (degrees).");
  prm.declare("Start time", "0", P::Double(0.0), "a number >= 0 (s)",
              "harmonic and pulse: model time at which f starts (s); 0 before.");
  prm.declare("End time of motion", "0", P::Double(0.0),
              "a number >= 0 (s; 0: none), above 'Start time'",
              "harmonic: model time at which f stops (s); 0 after.");
  prm.declare("Pulse duration", "1", P::Double(), "a number > 0 (s)",
              "pulse: duration of the half sine (s).");
}

TimeFunction parse_time_function(const ParameterFile& prm, bool acceleration_allowed,
                                 const std::string& why_not)
{
  const std::string kind = prm.get("Time function");
  const bool acceleration = prm.get("Input") == "acceleration";
  const bool baseline = prm.get_bool("Baseline correction");
  const std::string table = prm.get("Time table");
  if (kind == "none")
  {
    if (!table.empty())
      throw prm.error("Time table", "is given but 'Time function' is none",
                      "empty, or 'Time function = table'");
    if (acceleration)
      throw prm.error("Input", "acceleration needs a 'Time function'",
                      "value with 'Time function = none'; acceleration with a table, harmonic or "
                      "pulse");
    if (baseline)
      throw prm.error("Baseline correction", "is for an acceleration input",
                      "false unless 'Input = acceleration'");
    return TimeFunction{};
  }
  if (acceleration && !acceleration_allowed)
    throw prm.error("Input", "acceleration drives a velocity", why_not);
  if (baseline && !acceleration)
    throw prm.error("Baseline correction", "is for an acceleration input",
                    "false unless 'Input = acceleration'");
  if (kind != "table" && !table.empty())
    throw prm.error("Time table", "is given but 'Time function' is " + kind,
                    "empty, or 'Time function = table'");
  TimeFunction f;
  if (kind == "table")
  {
    if (table.empty())
      throw prm.error("Time table", "is empty but 'Time function' is table",
                      "a CSV file of lines 'time, value'");
    std::filesystem::path path(table);
    if (path.is_relative())
      path = std::filesystem::path(prm.file_of("Time table")).parent_path() / path;
    try
    {
      f = read_time_table(path.string());
    }
    catch (const InputError& e)
    {
      throw prm.error("Time table", e.what(),
                      "a CSV file of lines 'time, value' (two finite numbers, times increasing, "
                      "at least two lines; '#' lines and one header line skipped)");
    }
  }
  else
  {
    f.kind = kind == "harmonic" ? TimeFunction::Kind::harmonic : TimeFunction::Kind::pulse;
    f.amplitude = prm.get_double("Amplitude");
    f.start = prm.get_double("Start time");
    if (kind == "harmonic")
    {
      f.frequency = prm.get_double("Frequency");
      if (!(f.frequency > 0.0))
        throw prm.error("Frequency", "must be positive", "a number > 0 (Hz)");
      f.phase = prm.get_double("Phase") * pi / 180.0;
      const double end = prm.get_double("End time of motion");
      if (end > 0.0 && end <= f.start)
        throw prm.error("End time of motion", "is not after 'Start time'",
                        "0 (none) or a time after 'Start time' (s)");
      if (end > 0.0)
        f.end = end;
      else if (baseline)
        throw prm.error("Baseline correction", "needs a record that ends",
                        "an 'End time of motion' for a harmonic with baseline correction");
    }
    else
    {
      const double duration = prm.get_double("Pulse duration");
      if (!(duration > 0.0))
        throw prm.error("Pulse duration", "must be positive", "a number > 0 (s)");
      f.end = f.start + duration;
    }
  }
  if (acceleration)
    f.integrate_acceleration(baseline);
  return f;
}

} // namespace talus
