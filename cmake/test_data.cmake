# Where the tests and tools read real data from. Each data set (broad, gpsd-logs, wmm) is the
# full set in ${HEADINGD_SHARED_DIR}/data/<set> when that folder is there (../shared beside
# the checkout, as in CI), else the repository's subset in tests/data/<set> (README.md there
# names each file, its source and licence). A clone with nothing beside it therefore passes the
# whole suite; with ../shared the tests run on more data. Each test prints the set it used
# ("data: <folder> (<kind>, <n> <files>)").
#
# The choice is made when CMake configures: after adding or removing ../shared, configure
# again (cmake -S . -B build) to switch.

# headingd_data_set(<set> <dir_var> <kind_var>): the folder of <set> and "full set" or
# "in-repo subset".
function(headingd_data_set set dir_var kind_var)
  set(full "${HEADINGD_SHARED_DIR}/data/${set}")
  if(IS_DIRECTORY "${full}")
    get_filename_component(full "${full}" REALPATH)
    set(${dir_var} "${full}" PARENT_SCOPE)
    set(${kind_var} "full set" PARENT_SCOPE)
  else()
    set(${dir_var} "${PROJECT_SOURCE_DIR}/tests/data/${set}" PARENT_SCOPE)
    set(${kind_var} "in-repo subset" PARENT_SCOPE)
  endif()
endfunction()

# headingd_target_data_set(<target> <set>): compile definitions HEADINGD_<SET>_DIR and
# HEADINGD_<SET>_KIND (gpsd-logs -> HEADINGD_GPSD_LOGS_DIR) for tests/support/test_data.hpp.
function(headingd_target_data_set target set)
  headingd_data_set(${set} dir kind)
  string(TOUPPER "${set}" macro)
  string(REPLACE "-" "_" macro "${macro}")
  target_compile_definitions(${target} PRIVATE HEADINGD_${macro}_DIR="${dir}" HEADINGD_${macro}_KIND="${kind}")
  target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR}/tests/support)
endfunction()

foreach(set broad gpsd-logs wmm)
  headingd_data_set(${set} dir kind)
  message(STATUS "Test data ${set}: ${dir} (${kind})")
endforeach()
