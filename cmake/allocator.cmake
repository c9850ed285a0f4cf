# The allocator the executables that run whole simulations link (maneuvermap, maneuvermap_bench):
# gperftools' thread-caching malloc by default, whose per-thread caches serve the planner's small,
# short-lived buffers (docs/performance.md, "What changed in the fifteenth round"); or the system's. The
# libraries link none: a program that calls the planner keeps its own. Under sanitizers, which
# replace malloc themselves, always the system's.
set(MM_ALLOCATOR "tcmalloc" CACHE STRING "Allocator of the maneuvermap and maneuvermap_bench executables: tcmalloc or system")
set_property(CACHE MM_ALLOCATOR PROPERTY STRINGS tcmalloc system)
add_library(mm_allocator INTERFACE)
if(NOT MM_ALLOCATOR MATCHES "^(tcmalloc|system)$")
  message(FATAL_ERROR "MM_ALLOCATOR = '${MM_ALLOCATOR}': expected tcmalloc or system")
endif()
if(MM_ALLOCATOR STREQUAL "tcmalloc" AND NOT MM_SANITIZE)
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(MM_TCMALLOC REQUIRED IMPORTED_TARGET libtcmalloc_minimal)
  target_link_libraries(mm_allocator INTERFACE PkgConfig::MM_TCMALLOC)
  # Calls to malloc and free must reach it, not be folded by the compiler as builtins.
  target_compile_options(mm_allocator INTERFACE -fno-builtin-malloc -fno-builtin-calloc -fno-builtin-realloc
                                                -fno-builtin-free)
  set(MM_ALLOCATOR_NAME "tcmalloc")
else()
  set(MM_ALLOCATOR_NAME "system")
endif()
message(STATUS "maneuvermap: the executables use the ${MM_ALLOCATOR_NAME} allocator")
