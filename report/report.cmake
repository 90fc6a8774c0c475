# The assets of the HTML report (apps/html_report.cc), compiled into the CLI's library
# (movseg_app): Chart.js, which `npm ci` installs from the committed package-lock.json into
# <build>/report/node_modules (the repository holds no node_modules; after that first install the
# build needs no network), and report.js / report.css. Without npm the CLI is built all the same
# and `--html` says what is missing. Included by the top CMakeLists.txt: a custom command's
# output serves targets of its own directory only.
set(report_npm_dir ${CMAKE_BINARY_DIR}/report)
set(report_dir ${CMAKE_CURRENT_LIST_DIR})
set(report_chart_js ${report_npm_dir}/node_modules/chart.js/dist/chart.umd.js)
find_program(MOVSEG_NPM npm)
if(MOVSEG_NPM)
  file(MAKE_DIRECTORY ${report_npm_dir})
  add_custom_command(OUTPUT ${report_chart_js}
    COMMAND ${CMAKE_COMMAND} -E copy ${report_dir}/package.json
            ${report_dir}/package-lock.json ${report_npm_dir}
    COMMAND ${MOVSEG_NPM} ci --no-audit --no-fund --loglevel=error
    COMMAND ${CMAKE_COMMAND} -E touch_nocreate ${report_chart_js}
    WORKING_DIRECTORY ${report_npm_dir}
    DEPENDS ${report_dir}/package.json ${report_dir}/package-lock.json
    COMMENT "npm ci: Chart.js for the HTML report")
else()
  message(WARNING "npm not found: movseg bench/eval --html will not be available "
                  "(scripts/install-deps.sh installs npm)")
  set(report_chart_js "")
endif()

set(report_assets ${report_npm_dir}/report_assets.cc)
add_custom_command(OUTPUT ${report_assets}
  COMMAND ${CMAKE_COMMAND} -DOUTPUT=${report_assets} -DCHART_JS=${report_chart_js}
          -DREPORT_DIR=${report_dir} -P ${report_dir}/embed.cmake
  DEPENDS ${report_chart_js} ${report_dir}/report.js ${report_dir}/report.css ${report_dir}/embed.cmake
  COMMENT "Embedding the HTML report's assets")
target_sources(movseg_app PRIVATE ${report_assets})
