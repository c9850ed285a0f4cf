// Plans one step through the installed library: no obstacle, so the nominal command comes back;
// and reads a small CommonRoad file and measures its one road user.
#include <cstdio>

#include "mm/commonroad/measure.hpp"
#include "mm/commonroad/reader.hpp"
#include "mm/planner.hpp"
#include "mm/sim/path.hpp"

int main() {
  mm::plan_input in;
  in.ego.speed = 10.0;
  in.nominal = {0.5, 0.0};
  const mm::plan_result r = mm::plan(in);
  const mm::sim::path straight = mm::sim::path({{0.0, 0.0}, 0.0}).straight(10.0);
  const mm::commonroad::scenario recording = mm::commonroad::read_scenario_text(
      R"(<commonRoad timeStepSize="0.1" commonRoadVersion="2020a">
           <dynamicObstacle id="7"><type>car</type>
             <shape><rectangle><length>4.5</length><width>1.8</width></rectangle></shape>
             <initialState><position><point><x>0</x><y>0</y></point></position>
               <orientation><exact>0</exact></orientation><time><exact>0</exact></time>
               <velocity><exact>10</exact></velocity></initialState>
             <trajectory><state><position><point><x>1</x><y>0</y></point></position>
               <orientation><exact>0</exact></orientation><time><exact>1</exact></time>
               <velocity><exact>10</exact></velocity></state></trajectory>
           </dynamicObstacle>
         </commonRoad>)",
      "consumer.xml");
  mm::commonroad::measure_options options;
  options.agent = 7;
  const mm::commonroad::measurement m = mm::commonroad::measure(recording, options);
  const bool ok = r.ok() && r.command == in.nominal && straight.length() == 10.0 && m.steps.size() == 2 &&
                  mm::commonroad::room(m.steps[0].result) == 1.0;
  std::printf("%s\n", ok ? "consumer: planned through the installed package" : "consumer: unexpected result");
  return ok ? 0 : 1;
}
