# ctest -R python.the_installed_package: install the build tree into a temporary prefix, then import
# the installed package (and nothing of the build tree) and plan with it.
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD} --prefix ${WORK}/prefix RESULT_VARIABLE failed
                OUTPUT_QUIET)
if(failed)
  message(FATAL_ERROR "install failed")
endif()
set(ENV{PYTHONPATH} ${WORK}/prefix/${PACKAGE_DIR})
if(PRELOAD)
  set(ENV{LD_PRELOAD} ${PRELOAD})  # the sanitizer build: see tests/python/CMakeLists.txt
endif()
execute_process(COMMAND ${PYTHON} -c [=[
import pathlib
import maneuvermap as mm
assert mm.__file__.startswith(r""), mm.__file__
package = pathlib.Path(mm.__file__).parent
for typed in ("py.typed", "__init__.pyi", "sim.pyi", "commonroad.pyi", "_maneuvermap/__init__.pyi",
              "_maneuvermap/sim.pyi", "_maneuvermap/commonroad.pyi"):
    assert (package / typed).is_file(), f"{typed} is not installed"
result = mm.plan(mm.plan_input(ego=mm.ego_state(speed=10.0)))
assert list(result.mi_brake) == [1.0] * 17
run = mm.sim.run("s1-crossing")
print("installed package at", mm.__file__, "ran", run.scenario, "over", len(run.times), "instants")
]=] RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "the installed package failed")
endif()
