# libamha_image_codecs.so: the only target that links OpenCV's imgcodecs, which on Debian drags
# in ~140 shared libraries (GDAL, poppler, HDF5, ICU, ...; ~48 MB of RSS per process). The
# lattice layer dlopens it on first use (include/amha_planner/lattice/image_file.h), so planner
# processes fed by .cfg maps or OccupancyGrid messages never map them. It goes where the shared
# libraries go (catkin's devel/lib, installed beside them), else build/lib, which the loader
# also finds from build/bin, build/tests and build/fuzz (their ../lib).
find_package(OpenCV REQUIRED COMPONENTS core imgcodecs)
if(CMAKE_LIBRARY_OUTPUT_DIRECTORY)
  set(AMHA_LIBRARY_DIR ${CMAKE_LIBRARY_OUTPUT_DIRECTORY})
else()
  set(AMHA_LIBRARY_DIR ${CMAKE_BINARY_DIR}/lib)
endif()

add_library(amha_image_codecs MODULE src/image_codecs/image_codecs_module.cpp)
target_include_directories(amha_image_codecs SYSTEM PRIVATE ${OpenCV_INCLUDE_DIRS})
# Imported targets by name, not ${OpenCV_LIBS}: OpenCVConfig appends to that list on every
# find_package, so after this file it would carry imgcodecs into every later user.
target_link_libraries(amha_image_codecs PRIVATE opencv_core opencv_imgcodecs)
set_target_properties(amha_image_codecs PROPERTIES
  LIBRARY_OUTPUT_DIRECTORY ${AMHA_LIBRARY_DIR}
  CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
