# Commands that write several files, killed with SIGKILL and run again (kill_resume_test.sh,
# docs/reliability.md#interruption); included by CMakeLists.txt. Each part has its own folder.
foreach(part synth export)
  add_test(NAME cli.kill_resume.${part}
    COMMAND bash ${LH_CLI_SCRIPTS}/kill_resume_test.sh ${LH_CLI_EXE} ${CMAKE_CURRENT_BINARY_DIR}/kill_resume_${part}
            ${part})
  set_tests_properties(cli.kill_resume.${part} PROPERTIES TIMEOUT 120 LABELS cli
    PASS_REGULAR_EXPRESSION "all cases passed")
endforeach()
if(TARGET lighthouse_net)
  foreach(part predict train)
    add_test(NAME cli.kill_resume.${part}
      COMMAND bash ${LH_CLI_SCRIPTS}/kill_resume_test.sh ${LH_CLI_EXE} ${CMAKE_CURRENT_BINARY_DIR}/kill_resume_${part}
              ${part})
    set_tests_properties(cli.kill_resume.${part} PROPERTIES TIMEOUT 240 LABELS cli
      PASS_REGULAR_EXPRESSION "all cases passed")
  endforeach()
endif()
