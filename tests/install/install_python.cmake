# cmake -DBUILD_DIR=... -DWORK_DIR=... -DPYTHON=... -DPYTHON_DIR=... -P install_python.cmake
#
# Installs the build into WORK_DIR/prefix and checks the installed Python package there: it
# imports from PREFIX/PYTHON_DIR with its type stubs, `python3 -m movseg` runs the installed CLI
# (not the build tree's), and `movseg --version` and `movseg.__version__` agree.

include(${CMAKE_CURRENT_LIST_DIR}/run.cmake)

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

set(package ${prefix}/${PYTHON_DIR}/movseg)
foreach(file __init__.py __init__.pyi py.typed _build_info.py)
  if(NOT EXISTS ${package}/${file})
    message(FATAL_ERROR "not installed: ${package}/${file}")
  endif()
endforeach()

set(python ${CMAKE_COMMAND} -E env PYTHONPATH=${prefix}/${PYTHON_DIR} PYTHONDONTWRITEBYTECODE=1
    ${PYTHON})
# (No ';' in the code: it would split CMake's argument.)
run(${python} -c "from movseg.__main__ import cli_path\nprint(cli_path())")
if(NOT output STREQUAL "${prefix}/bin/movseg")
  message(FATAL_ERROR "the installed package runs '${output}', not ${prefix}/bin/movseg")
endif()
run(${python} -c "import movseg\nprint('movseg', movseg.__version__)")
set(module_version "${output}")
run(${python} -m movseg --version)
if(NOT output STREQUAL module_version)
  message(FATAL_ERROR "movseg --version says '${output}', the module '${module_version}'")
endif()

file(REMOVE_RECURSE ${WORK_DIR})
