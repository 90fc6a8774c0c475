# cmake -DBUILD_DIR=... -DEXAMPLE_DIR=... -DWORK_DIR=... -P install_and_build_examples.cmake
#
# Installs the build into WORK_DIR/prefix, builds examples/minimal against that prefix with its
# CMakeLists.txt (find_package) and with build_with_pkg_config.sh, and checks on a synthetic clip
# made by the installed CLI that the example writes the CLI's masks, bit for bit, and that the
# OpenCV drop-in finds the same moving pixels.

include(${CMAKE_CURRENT_LIST_DIR}/run.cmake)

set(prefix ${WORK_DIR}/prefix)
set(clip ${WORK_DIR}/clip)
file(REMOVE_RECURSE ${WORK_DIR})

run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
run(${prefix}/bin/movseg synth -o ${clip} --frames 5 --size 128x96)
run(${prefix}/bin/movseg segment ${clip}/frames -o ${clip}/cli_masks -q)

run(${CMAKE_COMMAND} -S ${EXAMPLE_DIR} -B ${WORK_DIR}/build -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_PREFIX_PATH=${prefix})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)

file(MAKE_DIRECTORY ${clip}/example_masks)
run(${WORK_DIR}/build/segment_video ${clip}/frames/%05d.png ${clip}/example_masks)
set(segment_output "${output}")
# The clip's movers are found by its last frame: equal empty masks would prove nothing below.
if(NOT segment_output MATCHES "frame 4: [1-9][0-9]* moving pixels")
  message(FATAL_ERROR "segment_video found nothing moving on the last frame:\n${segment_output}")
endif()
run(${WORK_DIR}/build/drop_in ${clip}/frames/%05d.png)
if(NOT output STREQUAL segment_output)
  message(FATAL_ERROR "drop_in and segment_video disagree:\n${output}\n---\n${segment_output}")
endif()
foreach(index RANGE 4)
  string(SUBSTRING "0000${index}" 0 5 name)  # index < 10
  run(${CMAKE_COMMAND} -E compare_files ${clip}/cli_masks/${name}.png ${clip}/example_masks/${name}.png)
endforeach()

# The same program through pkg-config, linked against the installed shared library, which it
# finds at run time by the RUNPATH the .pc file's flags record: no LD_LIBRARY_PATH.
file(GLOB pc_dirs ${prefix}/lib*/pkgconfig ${prefix}/lib/*/pkgconfig)
file(COPY ${EXAMPLE_DIR}/main.cc DESTINATION ${WORK_DIR}/pkg-config)
run(${CMAKE_COMMAND} -E env PKG_CONFIG_PATH=${pc_dirs}
    sh -c "cd ${WORK_DIR}/pkg-config && sh ${EXAMPLE_DIR}/build_with_pkg_config.sh")
run(${CMAKE_COMMAND} -E env --unset=LD_LIBRARY_PATH
    ${WORK_DIR}/pkg-config/segment_video ${clip}/frames/%05d.png ${WORK_DIR}/pkg-config)
if(NOT output STREQUAL segment_output)
  message(FATAL_ERROR "the pkg-config build disagrees:\n${output}\n---\n${segment_output}")
endif()

file(REMOVE_RECURSE ${WORK_DIR})
