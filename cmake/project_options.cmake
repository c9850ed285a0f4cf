# Warning and sanitizer settings shared by every target of the project.
add_library(mm_project_options INTERFACE)
target_compile_options(mm_project_options INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wold-style-cast
  -Wcast-align -Woverloaded-virtual -Wnull-dereference -Wdouble-promotion
  -Wformat=2 -Wimplicit-fallthrough -Wmissing-declarations)
# The libraries are position-independent code when the Python module links them (MM_BUILD_PYTHON):
# no function of ours is interposed at run time, so the compiler may inline across them as in an
# executable (GCC assumes otherwise under -fPIC; clang does not).
target_compile_options(mm_project_options INTERFACE $<$<CXX_COMPILER_ID:GNU>:-fno-semantic-interposition>)
if(MM_WARNINGS_AS_ERRORS)
  target_compile_options(mm_project_options INTERFACE -Werror)
endif()
if(MM_SANITIZE)
  target_compile_options(mm_project_options INTERFACE
    -fsanitize=${MM_SANITIZE} -fno-omit-frame-pointer -fno-sanitize-recover=all)
  target_link_options(mm_project_options INTERFACE -fsanitize=${MM_SANITIZE})
endif()
