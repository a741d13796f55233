# Verdicts to trust: model validation, convergence and invariants in the
# problem's own scales, shipped scenes on their defaults, bounded runs.
foreach(name hb_model_test convergence_scales_test invariant_scales_test shipped_scenes_test)
  add_executable(${name} ${name}.cpp)
  target_link_libraries(${name} PRIVATE eqhb_test_support)
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60)
endforeach()
set(EXPECT_EXIT ${CMAKE_CURRENT_SOURCE_DIR}/expect_exit.sh)
set(CONTACT ${PROJECT_SOURCE_DIR}/problems/contact.toml)
add_test(NAME cli.contact_needs_the_constant_term
         COMMAND ${EXPECT_EXIT} 2 "harmonic_balance.set = \"odd\": law\\[0\\] \\(signorini\\) needs the constant term"
                 ${EQHB_CLI} solve ${CONTACT} --set harmonic_balance.set=odd --full)
# The contact scene converges from a cold start on its own defaults.
add_test(NAME cli.contact_defaults_converge
         COMMAND ${EXPECT_EXIT} 0 "dogleg: converged" ${EQHB_CLI} solve ${CONTACT})

# Command-line parse errors are bad input: exit 2 with CLI11's message; --help exits 0.
add_test(NAME cli.unknown_option COMMAND ${EXPECT_EXIT} 2 "not expected: --nope"
         ${EQHB_CLI} solve ${SCENE} --nope)
add_test(NAME cli.unconvertible_value COMMAND ${EXPECT_EXIT} 2 "Could not convert: --omega = abc"
         ${EQHB_CLI} solve ${SCENE} --omega abc)
add_test(NAME cli.no_subcommand COMMAND ${EXPECT_EXIT} 2 "subcommand is required" ${EQHB_CLI})
add_test(NAME cli.help_exits_0 COMMAND ${EXPECT_EXIT} 0 "solve" ${EQHB_CLI} --help)
