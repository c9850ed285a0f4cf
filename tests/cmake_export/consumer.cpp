// Plans one step through the installed library: no obstacle, so the nominal command comes back.
#include <cstdio>

#include "mm/planner.hpp"
#include "mm/sim/path.hpp"

int main() {
  mm::plan_input in;
  in.ego.speed = 10.0;
  in.nominal = {0.5, 0.0};
  const mm::plan_result r = mm::plan(in);
  const mm::sim::path straight = mm::sim::path({{0.0, 0.0}, 0.0}).straight(10.0);
  const bool ok = r.ok() && r.command == in.nominal && straight.length() == 10.0;
  std::printf("%s\n", ok ? "consumer: planned through the installed package" : "consumer: unexpected result");
  return ok ? 0 : 1;
}
