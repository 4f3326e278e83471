# Fails when a source under FOLDER builds an acceleration structure outside the files that may:
# every tracer borrows the scene's structures from lighting/common/scene_accel.{h,cpp}, which
# alone builds, refits and rebuilds them (gpu/acceleration_structure.{h,cpp} is the builder it
# calls; gpu/self_test.cpp builds a one-triangle scene to check the device). A path or plugin
# that builds its own set fails here, as it fails the GPU test that counts the builds
# (tests/gpu/test_scene_accel.cpp).
#   -DFOLDER=<folder>
file(GLOB_RECURSE sources "${FOLDER}/*.cpp" "${FOLDER}/*.h")
if(NOT sources)
  message(FATAL_ERROR "no sources under ${FOLDER}")
endif()
set(allowed "gpu/acceleration_structure\\.(h|cpp)$|gpu/self_test\\.cpp$|lighting/common/scene_accel\\.(h|cpp)$")
set(bad "")
foreach(f IN LISTS sources)
  if(f MATCHES "${allowed}")
    continue()
  endif()
  file(STRINGS "${f}" lines REGEX "buildBottomLevel|buildTopLevel|TopLevelBuilder|recordRefit|recordRebuild")
  foreach(line IN LISTS lines)
    string(STRIP "${line}" line)
    string(APPEND bad "\n  ${f}: ${line}")
  endforeach()
endforeach()
if(bad)
  message(FATAL_ERROR "only SceneAccel builds acceleration structures (lighting/common/scene_accel.h); these sources build their own:${bad}")
endif()
list(LENGTH sources n)
message(STATUS "${n} sources under ${FOLDER}: only SceneAccel builds acceleration structures")
