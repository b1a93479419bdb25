// The TimeSensor rules of VRML97, case by case.
#include <catch2/catch.hpp>

#include "engine/scene/time_model.h"

using namespace fscript::scene;

static TimeSensorState at(double start, double stop, double cycle, bool loop, double now, bool enabled = true) {
  return evaluate_time_sensor({start, stop, cycle, loop, enabled}, now);
}

TEST_CASE("time: before startTime nothing is sent") {
  auto s = at(2, 0, 1, false, 1.5);
  CHECK(!s.ever_active);
  CHECK(!s.active);
  CHECK(s.fraction == 0);
}

TEST_CASE("time: at startTime the fraction is 0 and the sensor is active") {
  auto s = at(2, 0, 1, false, 2);
  CHECK(s.active);
  CHECK(s.fraction == 0);
  CHECK(s.cycle_time == 2);
}

TEST_CASE("time: mid-cycle fraction") {
  CHECK(at(0, 0, 4, false, 1).fraction == Approx(0.25));
  CHECK(at(1, 0, 4, true, 4).fraction == Approx(0.75));
}

TEST_CASE("time: the end of a single cycle gives 1.0 and stops") {
  auto s = at(0, 0, 2, false, 2);
  CHECK(!s.active);
  CHECK(s.ever_active);
  CHECK(s.fraction == 1.0);
  auto later = at(0, 0, 2, false, 100);
  CHECK(later.fraction == 1.0);  // the last event stays
  CHECK(!later.active);
}

TEST_CASE("time: a looping sensor wraps, and a whole number of cycles gives 1.0") {
  CHECK(at(0, 0, 2, true, 4).fraction == 1.0);
  CHECK(at(0, 0, 2, true, 4).active);
  CHECK(at(0, 0, 2, true, 4.5).fraction == Approx(0.25));
  CHECK(at(0, 0, 2, true, 4.5).cycle_time == 4);
  CHECK(at(0, 0, 2, true, 4).cycle_time == 2);
}

TEST_CASE("time: stopTime ends the sensor with the fraction at stopTime") {
  auto s = at(0, 3, 2, true, 10);
  CHECK(!s.active);
  CHECK(s.fraction == Approx(0.5));
  auto exact = at(0, 4, 2, true, 10);
  CHECK(exact.fraction == 1.0);
  auto single = at(0, 1, 4, false, 10);  // stopTime before the cycle ends
  CHECK(single.fraction == Approx(0.25));
}

TEST_CASE("time: a stopTime at or before startTime is ignored") {
  CHECK(at(5, 5, 2, true, 100).active);
  CHECK(at(5, 1, 2, true, 100).active);
  CHECK(at(5, 1, 2, false, 6).fraction == Approx(0.5));
}

TEST_CASE("time: a disabled sensor never runs") {
  auto s = at(0, 0, 1, true, 0.5, false);
  CHECK(!s.ever_active);
  CHECK(s.fraction == 0);
}

TEST_CASE("time: a sensor that started before load") {
  auto looping = at(-3, -5, 2, true, 0.5);  // running at load, cycles counted from startTime
  CHECK(looping.active);
  CHECK(looping.fraction == Approx(0.75));
  auto over = at(-3, 0, 2, false, 0.5);  // its only cycle ended before load: no event ever
  CHECK(!over.ever_active);
  CHECK(over.fraction == 0);
}

TEST_CASE("time: node t from the fraction and timeSpan") {
  CHECK(node_time(0, 0, 1) == 0);
  CHECK(node_time(0.5, -3.1415926, 3.1415926) == Approx(0));
  CHECK(node_time(1, 2, 5) == 5);
}

TEST_CASE("time: an active period that ends exactly at load never sends an event; a moment later it does") {
  auto at_load = at(-2, -5, 2, false, 1);  // [-2, 0]: over when the world starts
  CHECK(!at_load.ever_active);
  CHECK(at_load.fraction == 0);
  auto stopped_at_load = at(-2, 0, 5, true, 1);  // stopTime 0 ends it at load too
  CHECK(!stopped_at_load.ever_active);
  auto after = at(-2, -5, 2.5, false, 1);  // [-2, 0.5]: its last event (at 0.5) says 1.0
  CHECK(after.ever_active);
  CHECK(!after.active);
  CHECK(after.fraction == 1.0);
  CHECK(after.time_of_last_event == 0.5);
  CHECK(after.cycle_time == 0);  // cycleTime was sent at -2, seen as the world's start
}

TEST_CASE("time: active up to, not at, the end of the period; cycleTime at each cycle's start") {
  CHECK(at(1, 0, 2, false, 2.999).active);
  CHECK(!at(1, 0, 2, false, 3).active);
  CHECK(at(1, 0, 2, false, 3).fraction == 1.0);
  CHECK(at(1, 0, 2, false, 3).cycle_time == 1);  // the end of the only cycle still belongs to it
  CHECK(at(1, 0, 2, true, 5).cycle_time == 3);
  CHECK(at(1, 0, 2, true, 5.5).cycle_time == 5);
  CHECK(at(1, 0, 2, true, 1).fraction == 0);   // at startTime itself
  CHECK(!at(1, 0, 2, true, 0.999).ever_active);
}
