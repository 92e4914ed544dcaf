# cmake -P: runs the skip probes (skip_probe.cpp) in a throw-away ctest project with the
# SKIP_RETURN_CODE every Catch test gets (cmake/VtTarget.cmake) and checks ctest's verdicts and
# summary. -DPROBE=<vt_skip_probe> -DWORK=<scratch folder> -DSKIP_CODE=<VT_TEST_SKIP_CODE>
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(cases probe_skip probe_pass probe_fail_then_skip)
set(script "")
foreach(name ${cases})
  string(APPEND script "add_test(${name} \"${PROBE}\" \"[${name}]\")\n"
                       "set_tests_properties(${name} PROPERTIES SKIP_RETURN_CODE ${SKIP_CODE})\n")
endforeach()
# Several cases in one process (a display group): one skip makes the whole run a skip.
string(APPEND script "add_test(probe_group \"${PROBE}\" \"[probe_skip],[probe_pass]\")\n"
                     "set_tests_properties(probe_group PROPERTIES SKIP_RETURN_CODE ${SKIP_CODE})\n")
# A test with a pass expression is still skipped, not failed, when it exits with the skip code.
string(APPEND script "add_test(probe_skip_with_regex \"${PROBE}\" \"[probe_skip]\")\n"
                     "set_tests_properties(probe_skip_with_regex PROPERTIES SKIP_RETURN_CODE ${SKIP_CODE} "
                     "PASS_REGULAR_EXPRESSION \"never printed\")\n")
file(WRITE ${WORK}/CTestTestfile.cmake "${script}")
execute_process(COMMAND ${CMAKE_CTEST_COMMAND} --test-dir ${WORK} OUTPUT_VARIABLE out ERROR_VARIABLE out)
message("${out}")
set(expected
  "probe_skip [.]+[*]+Skipped"
  "probe_pass [.]+ +Passed"
  "probe_fail_then_skip [.]+[*]+Failed"
  "probe_group [.]+[*]+Skipped"
  "probe_skip_with_regex [.]+[*]+Skipped"
  "The following tests did not run:"
  "probe_skip [(]Skipped[)]")
foreach(pattern ${expected})
  if(NOT out MATCHES "${pattern}")
    message(FATAL_ERROR "ctest's output lacks '${pattern}'")
  endif()
endforeach()
message("PASS: skipped probes are counted as skipped, failures stay failures")
