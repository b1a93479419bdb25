// TimeSensor evaluation. The rules, from the VRML97 standard:
//  - inactive before startTime; a stopTime <= startTime is ignored; disabled sensors never run;
//  - loop FALSE: active until startTime + cycleInterval or stopTime, whichever comes first;
//    loop TRUE: active until stopTime (forever when it is ignored);
//  - fraction = fractional part of (now - startTime) / cycleInterval, except that the end of a
//    cycle (a positive whole number of cycles) gives 1.0, not 0.0;
//  - when the sensor stops, its last event carries the fraction at the stop time;
//  - nothing happens before load (time 0): a sensor whose active period ended before load never
//    sends an event.
#include "engine/scene/time_model.h"

#include <algorithm>
#include <cmath>

namespace fscript::scene {

namespace {
double fraction_at(double elapsed, double cycle) {
  double cycles = elapsed / cycle;
  double f = cycles - std::floor(cycles);
  return (f == 0 && elapsed > 0) ? 1.0 : f;
}
}  // namespace

TimeSensorState evaluate_time_sensor(const TimeSensorFields& f, double now) {
  TimeSensorState s;
  if (!f.enabled || !(f.cycle_interval > 0) || now < f.start_time) return s;
  const double inf = std::numeric_limits<double>::infinity();
  double stop = f.stop_time > f.start_time ? f.stop_time : inf;
  double end = f.loop ? stop : std::min(f.start_time + f.cycle_interval, stop);
  if (end <= 0) return s;  // its whole active period lies before load
  double at = std::min(now, end);
  double elapsed = at - f.start_time;
  s.ever_active = true;
  s.active = now < end;
  s.fraction = fraction_at(elapsed, f.cycle_interval);
  double whole = std::floor(elapsed / f.cycle_interval);
  if (s.fraction == 1.0 && whole > 0) whole -= 1;  // the end of a cycle still belongs to it
  s.cycle_time = std::max(0.0, f.start_time + whole * f.cycle_interval);
  s.time_of_last_event = std::max(0.0, at);
  return s;
}

}  // namespace fscript::scene
