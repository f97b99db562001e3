# `mirror --bug-report FILE`: runs the mirror briefly and writes a tarball holding what a
# developer needs. Checks the exit code, the files in the tarball and what a few of them say.
#   cmake -DMIRROR=<exe> -DOUT=<dir> -P bug_report.cmake

file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
execute_process(
  COMMAND ${MIRROR} --source synthetic --display headless:${OUT}/display
          --set "state.dir=\"${OUT}\"" --bug-report ${OUT}/report.tar.gz
  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "mirror --bug-report exited ${code}\n${out}${err}")
endif()
execute_process(COMMAND tar -xzf ${OUT}/report.tar.gz -C ${OUT} RESULT_VARIABLE code)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "the report is not a gzip tarball")
endif()
foreach(name status.txt status.json selftest.txt config.toml log.txt devices.txt journal.txt
             snapshot.png)
  if(NOT EXISTS ${OUT}/${name})
    message(FATAL_ERROR "the report has no ${name}\n${out}${err}")
  endif()
endforeach()
file(READ ${OUT}/status.txt status)
file(READ ${OUT}/selftest.txt selftest)
file(READ ${OUT}/config.toml config)
file(READ ${OUT}/devices.txt devices)
file(READ ${OUT}/status.json json)
foreach(pair "status:^mirror [0-9.]+ .*source: synthetic" "selftest:PASS camera: synthetic"
             "selftest:selftest: " "config:\\[source\\].*spec = \"synthetic\""
             "devices:V4L2 capture devices:" "json:^\\{\"version\":\"[0-9.]+\",.*\"stages\":\\[")
  string(FIND "${pair}" ":" colon)
  string(SUBSTRING "${pair}" 0 ${colon} var)
  math(EXPR start "${colon} + 1")
  string(SUBSTRING "${pair}" ${start} -1 regex)
  if(NOT "${${var}}" MATCHES "${regex}")
    message(FATAL_ERROR "${var} does not match ${regex}:\n${${var}}")
  endif()
endforeach()
if(NOT err MATCHES "bug-report: wrote ${OUT}/report.tar.gz")
  message(FATAL_ERROR "no 'bug-report: wrote' line:\n${err}")
endif()
