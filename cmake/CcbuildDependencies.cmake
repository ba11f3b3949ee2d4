# Finds every third-party package ccbuild uses, all from Debian 12, and gives each an
# imported target. A missing package stops configuration with the apt package to install.

function(ccbuild_require found what package)
  if(NOT ${found})
    message(FATAL_ERROR
      "ccbuild: ${what} not found. Install the Debian package '${package}' "
      "(or run scripts/install-deps.sh as root, which installs everything).")
  endif()
endfunction()

# --- The mission's four packages: LCM, Eigen, OMPL, urdfdom -------------------------
find_package(PkgConfig QUIET)
ccbuild_require(PKG_CONFIG_FOUND "pkg-config" "pkg-config")
# Debian's LCM 1.3.1 ships no CMake package; pkg-config 'lcm' also needs glib's .pc.
pkg_check_modules(LCM QUIET IMPORTED_TARGET lcm)
ccbuild_require(LCM_FOUND "LCM (pkg-config module 'lcm')" "liblcm-dev libglib2.0-dev")
find_program(LCM_GEN_EXECUTABLE lcm-gen)
ccbuild_require(LCM_GEN_EXECUTABLE "lcm-gen" "liblcm-bin")
if(NOT TARGET ccbuild::lcm)
  add_library(ccbuild::lcm INTERFACE IMPORTED)
  target_link_libraries(ccbuild::lcm INTERFACE PkgConfig::LCM)
endif()

find_package(Eigen3 3.3 QUIET NO_MODULE)
ccbuild_require(Eigen3_FOUND "Eigen 3" "libeigen3-dev")

find_package(ompl QUIET)
ccbuild_require(OMPL_FOUND "OMPL" "libompl-dev")
# OMPL 1.5.2 exports variables, not a target; its libraries pull in Boost and ODE.
find_package(Boost QUIET COMPONENTS serialization filesystem system)
ccbuild_require(Boost_FOUND "Boost serialization/filesystem/system"
  "libboost-serialization-dev libboost-filesystem-dev libboost-system-dev")
find_library(ODE_LIBRARY ode)
ccbuild_require(ODE_LIBRARY "ODE" "libode-dev")
if(NOT TARGET ccbuild::ompl)
  add_library(ccbuild::ompl INTERFACE IMPORTED)
  target_include_directories(ccbuild::ompl SYSTEM INTERFACE ${OMPL_INCLUDE_DIRS})
  target_link_libraries(ccbuild::ompl INTERFACE ${OMPL_LIBRARIES}
    Boost::serialization Boost::filesystem Boost::system)
endif()

find_package(urdfdom QUIET)
ccbuild_require(urdfdom_FOUND "urdfdom" "liburdfdom-dev")

# --- Everything else the product uses ---------------------------------------------
# Howard Hinnant's date library with its time-zone part built on the system's tzdata
# (USE_OS_TZDB): GCC 12's <chrono> has no time zones yet.
find_package(date QUIET CONFIG)
ccbuild_require(date_FOUND "the date library (date::date-tz)" "libhowardhinnant-date-dev tzdata")
find_package(fcl QUIET)
ccbuild_require(fcl_FOUND "FCL" "libfcl-dev")

find_package(lemon QUIET)
if(NOT lemon_FOUND)
  find_path(LEMON_INCLUDE_DIR lemon/matching.h)
  set(lemon_FOUND ${LEMON_INCLUDE_DIR})
endif()
ccbuild_require(lemon_FOUND "LEMON" "liblemon-dev")
if(NOT TARGET ccbuild::lemon)
  add_library(ccbuild::lemon INTERFACE IMPORTED)
  # Matching and minimum cut are header-only templates; the LP interface (GLPK
  # underneath, as Debian builds LEMON) is in the shared library.
  find_library(LEMON_SHARED_LIBRARY NAMES lemon)
  ccbuild_require(LEMON_SHARED_LIBRARY "LEMON's library" "liblemon-dev")
  target_include_directories(ccbuild::lemon SYSTEM INTERFACE ${LEMON_INCLUDE_DIR})
  target_link_libraries(ccbuild::lemon INTERFACE ${LEMON_SHARED_LIBRARY})
endif()

find_package(yaml-cpp QUIET)
ccbuild_require(yaml-cpp_FOUND "yaml-cpp" "libyaml-cpp-dev")
find_package(nlohmann_json 3.10 QUIET)
ccbuild_require(nlohmann_json_FOUND "nlohmann-json" "nlohmann-json3-dev")
find_package(CLI11 QUIET)
ccbuild_require(CLI11_FOUND "CLI11" "libcli11-dev")
find_package(SQLite3 QUIET)
ccbuild_require(SQLite3_FOUND "SQLite 3" "libsqlite3-dev")
find_package(Threads REQUIRED)

if(CCBUILD_BUILD_TESTS)
  find_package(GTest QUIET)
  ccbuild_require(GTest_FOUND "GoogleTest" "libgtest-dev")
  include(GoogleTest)
endif()
if(CCBUILD_BUILD_BENCH)
  find_package(benchmark QUIET)
  ccbuild_require(benchmark_FOUND "Google Benchmark" "libbenchmark-dev")
endif()
