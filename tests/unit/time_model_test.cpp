// The TimeSensor rules of VRML97, case by case.
#include <catch2/catch.hpp>

#include "runtime/scene/time_model.h"

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
