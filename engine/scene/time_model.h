#pragma once
// The time model: a VRML97 TimeSensor (ISO/IEC 14772-1, 6.50 and 4.6.9) evaluated at a clock
// value, and the mapping of a fraction to a node's t through its timeSpan. The file is loaded at
// time 0 and nothing happens before load; times in the file are on the same clock.
#include <limits>

namespace fscript::scene {

struct TimeSensorFields {
  double start_time = 0;
  double stop_time = 0;
  double cycle_interval = 1;  // must be > 0 (the scene layer reports anything else)
  bool loop = false;
  bool enabled = true;
};

struct TimeSensorState {
  bool ever_active = false;  // has it sent any fraction_changed by `now`?
  bool active = false;       // isActive at `now`
  double fraction = 0;       // the last fraction_changed sent (0 if none)
  double cycle_time = 0;     // the start of the current (or last) cycle
  double time_of_last_event = 0;
};

// State of a TimeSensor whose fields never change, observed at `now` (seconds after load).
TimeSensorState evaluate_time_sensor(const TimeSensorFields& f, double now);

// A node's t for a shape fraction: timeSpan[0] + fraction * (timeSpan[1] - timeSpan[0]).
inline double node_time(double fraction, double span0, double span1) { return span0 + fraction * (span1 - span0); }

}  // namespace fscript::scene
