# Verdicts to trust: model validation, convergence and invariants in the
# problem's own scales, shipped scenes on their defaults, bounded runs.
foreach(name hb_model_test convergence_scales_test unit_systems_test scale_free_width_test invariant_scales_test shipped_scenes_test)
  add_executable(${name} ${name}.cpp)
  target_link_libraries(${name} PRIVATE eqhb_test_support)
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60)
endforeach()
target_link_libraries(unit_systems_test PRIVATE eqhb_app)  # sweeps as `eqhb sweep` sweeps
target_link_libraries(shipped_scenes_test PRIVATE eqhb_app)  # a [[preload]] settled as `eqhb solve` settles it
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
# Numbers beyond the double range are refused, not rounded to 0 or the largest double.
add_test(NAME cli.omega_underflows COMMAND ${EXPECT_EXIT} 2 "--omega: 1e-400 underflows to 0; not representable"
         ${EQHB_CLI} solve ${SCENE} --omega 1e-400)
add_test(NAME cli.set_underflows
         COMMAND ${EXPECT_EXIT} 2 "law\\[0\\]\\.muN = 1e-400: underflows to 0; not representable"
                 ${EQHB_CLI} solve ${SCENE} --set law[0].muN=1e-400)
add_test(NAME cli.tolerance_overflows COMMAND ${EXPECT_EXIT} 2 "--tolerance: 1e999 overflows; not representable"
         ${EQHB_CLI} solve ${SCENE} --tolerance 1e999)
add_test(NAME cli.no_subcommand COMMAND ${EXPECT_EXIT} 2 "subcommand is required" ${EQHB_CLI})
add_test(NAME cli.help_exits_0 COMMAND ${EXPECT_EXIT} 0 "solve" ${EQHB_CLI} --help)

# Time runs are bounded and say why they stopped; stribeck.toml settles on
# its own [time_reference] defaults. At h = 1e-4 a period takes about 0.2 s
# and the run from rest is far from periodic after the few that fit in 1 s
# (or 0.5 s).
set(STRIBECK ${PROJECT_SOURCE_DIR}/problems/stribeck.toml)
add_test(NAME cli.simulate_wall_clock_limit
         COMMAND ${EXPECT_EXIT} 1 "no periodic steady state within --max-seconds = 1 \\([0-9]+ periods, change"
                 ${EQHB_CLI} simulate ${STRIBECK} --step 1e-4 --max-seconds 1)
add_test(NAME cli.simulate_progress
         COMMAND ${EXPECT_EXIT} 1 "stribeck simulate  period 1/3  elapsed .*  change .* \\(periodic at 1e-09\\)"
                 ${EQHB_CLI} --progress simulate ${STRIBECK} --periods 3)
add_test(NAME cli.stribeck_settles_on_its_defaults
         COMMAND ${EXPECT_EXIT} 0 "time reference: periodic after" ${EQHB_CLI} simulate ${STRIBECK})
add_test(NAME cli.simulate_command_line_over_scene_defaults
         COMMAND ${EXPECT_EXIT} 1 "NOT periodic after 2 periods.*h = 0.00999" ${EQHB_CLI} simulate ${STRIBECK}
                 --periods 2 --step 1e-2)
add_test(NAME cli.simulate_negative_max_seconds
         COMMAND ${EXPECT_EXIT} 2 "max seconds = -1: must be finite and >= 0" ${EQHB_CLI} simulate ${STRIBECK}
                 --max-seconds -1)
add_test(NAME cli.simulate_wall_clock_limit_json
         COMMAND ${EXPECT_EXIT} 1 "\"timed_out\": true" ${EQHB_CLI} simulate ${STRIBECK} --step 1e-4 --max-seconds 0.5 --json)

# --time-limit bounds the set-up too: the full system of a 2000-DOF beam on 200
# harmonics takes minutes to assemble and factor; it stops in its assembly.
add_test(NAME cli.solve_time_limit_covers_setup
         COMMAND ${EXPECT_EXIT} 1 "time limit of 0.5 s reached during set-up of the full system"
                 ${EQHB_CLI} solve ${PROJECT_SOURCE_DIR}/problems/beam-joint-large.toml --harmonics 200
                 --samples 1024 --full --time-limit 0.5)
set_tests_properties(cli.solve_time_limit_covers_setup PROPERTIES TIMEOUT 30)
# shoot on cubic at omega = 0.8 (the start does not converge) runs for minutes:
# --time-limit stops it, with progress, and no multipliers for an orbit not found.
set(CUBIC ${PROJECT_SOURCE_DIR}/problems/cubic.toml)
add_test(NAME cli.shoot_time_limit
         COMMAND ${EXPECT_EXIT} 1 "NOT converged: time limit reached after [0-9]+ Newton steps"
                 ${EQHB_CLI} shoot ${CUBIC} --omega 0.8 --time-limit 1 --fallback none)
add_test(NAME cli.shoot_unconverged_has_no_multipliers
         COMMAND ${EXPECT_EXIT} 1 "\"multipliers\": null"
                 ${EQHB_CLI} shoot ${CUBIC} --omega 0.8 --time-limit 1 --fallback none --json)
add_test(NAME cli.shoot_progress
         COMMAND ${EXPECT_EXIT} 1 "cubic shoot  Newton step [0-9]+/40  elapsed .* period maps"
                 ${EQHB_CLI} --progress shoot ${CUBIC} --omega 0.8 --time-limit 1 --fallback none)
# With the default path its harmonic-balance start converges (Ipopt) and the
# orbit is found in a fraction of a second.
if(EQHB_WITH_IPOPT)
  add_test(NAME cli.shoot_from_the_default_path
           COMMAND ${EXPECT_EXIT} 0 "stable \\(spectral radius 0.95"
                   ${EQHB_CLI} shoot ${CUBIC} --omega 0.8 --time-limit 20)
endif()
set_tests_properties(cli.shoot_time_limit cli.shoot_unconverged_has_no_multipliers cli.shoot_progress
                     PROPERTIES TIMEOUT 30)

# Bad input to the joint laws: exit 2, naming the field (parse-time checks,
# so each runs in milliseconds).
set(CONTACT_FRICTION ${PROJECT_SOURCE_DIR}/problems/contact-friction-2d.toml)
set(JENKINS ${PROJECT_SOURCE_DIR}/problems/jenkins-1d.toml)
set(LAP_VARYING ${PROJECT_SOURCE_DIR}/problems/lap-joint-varying.toml)
foreach(case
    "negative_mu|law\\[0\\]\\.mu = -0\\.1|${CONTACT_FRICTION}|law.mu=-0.1"
    "negative_preload|law\\[0\\]\\.preload = -1|${CONTACT_FRICTION}|law.preload=-1"
    "zero_k_t|law\\[0\\]\\.k_t = 0|${CONTACT_FRICTION}|law.k_t=0"
    "zero_k_n|law\\[0\\]\\.k_n = 0|${CONTACT_FRICTION}|law.form=\"compliant\";--set;law.k_n=0"
    "missing_k_n|law\\[0\\]\\.k_n = \\(missing\\)|${CONTACT_FRICTION}|law.form=\"compliant\""
    "normal_also_tangential|law\\[0\\]\\.dofs = 1: the normal DOF is also a tangential DOF|${CONTACT_FRICTION}|law.dofs=[1,1]"
    "odd_harmonics|harmonic_balance\\.set = \"odd\": law\\[0\\] \\(contact-friction\\) needs the constant term|${CONTACT_FRICTION}|harmonic_balance.set=\"odd\""
    "jenkins_negative_k_t|law\\[0\\]\\.k_t = -1|${JENKINS}|law.k_t=-1"
    "jenkins_negative_muN|law\\[0\\]\\.muN = -1|${JENKINS}|law.muN=-1"
    "elastic_friction_negative_mu|law\\[0\\]\\.mu = -0\\.1: friction coefficient must be >= 0|${LAP_VARYING}|law[0].mu=-0.1"
    "elastic_friction_nan_k_t|law\\[0\\]\\.k_t = nan: must be finite|${LAP_VARYING}|law[0].k_t=nan"
    "elastic_friction_negative_k_t|law\\[0\\]\\.k_t = -1|${LAP_VARYING}|law[0].k_t=-1"
    "elastic_friction_zero_k_n|law\\[0\\]\\.k_n = 0|${LAP_VARYING}|law[0].k_n=0"
    "elastic_friction_nan_gap|law\\[0\\]\\.gap = nan: must be finite|${LAP_VARYING}|law[0].gap=nan")
  string(REPLACE "|" ";" fields "${case}")
  list(GET fields 0 name)
  list(GET fields 1 pattern)
  list(GET fields 2 scene)
  list(SUBLIST fields 3 -1 sets)
  add_test(NAME cli.joint_bad_input.${name} COMMAND ${EXPECT_EXIT} 2 "${pattern}" ${EQHB_CLI} solve ${scene} --set ${sets})
endforeach()
# The time reference steps elastic-friction with its slider (3D, and 2D on
# the same scene): `eqhb compare` exits 0 within a bound on every
# displacement's L2 error (measured 2.0e-3 in 3D, 1.4e-3 in 2D at H = 15).
set(ELASTIC_FRICTION_3D ${PROJECT_SOURCE_DIR}/problems/elastic-friction-3d.toml)
add_test(NAME cli.elastic_friction_3d_compare_within_bound
         COMMAND ${PROJECT_SOURCE_DIR}/tests/cli/compare_within.sh 3e-3 ${EQHB_CLI} compare ${ELASTIC_FRICTION_3D})
add_test(NAME cli.elastic_friction_2d_compare_within_bound
         COMMAND ${PROJECT_SOURCE_DIR}/tests/cli/compare_within.sh 2e-3 ${EQHB_CLI} compare ${ELASTIC_FRICTION_3D}
                 --set law.dofs=[1,2])
# Shooting carries no slider state for elastic-friction: refused naming the
# law (between nodes, and on DOFs against the ground).
add_test(NAME cli.elastic_friction_shoot_refused
         COMMAND ${EXPECT_EXIT} 2 "a elastic-friction law between two nodes: exact orbits"
                 ${EQHB_CLI} shoot ${LAP_VARYING})
add_test(NAME cli.elastic_friction_grounded_shoot_refused
         COMMAND ${EXPECT_EXIT} 2 "law\\[0\\]\\.type = elastic-friction: exact orbits handle"
                 ${EQHB_CLI} shoot ${PROJECT_SOURCE_DIR}/tests/cli/bad/elastic-friction-no-k-n.toml --set law.k_n=3.0)
# An elastic-friction law needs [normal, tangent(s)] and its three constants
# (the DOF list is printed over lines: the field is checked in elastic_friction_test).
add_test(NAME cli.joint_bad_input.elastic_friction_one_dof
         COMMAND ${EXPECT_EXIT} 2 "\\]: an elastic-friction law acts on \\[normal, tangential\\] or"
                 ${EQHB_CLI} solve ${PROJECT_SOURCE_DIR}/tests/cli/bad/elastic-friction-one-dof.toml)
add_test(NAME cli.joint_bad_input.elastic_friction_missing_k_n
         COMMAND ${EXPECT_EXIT} 2 "law\\[0\\]\\.k_n = \\(missing\\): required"
                 ${EQHB_CLI} solve ${PROJECT_SOURCE_DIR}/tests/cli/bad/elastic-friction-no-k-n.toml)

# "Converged" means the law holds at any ρ and in any time unit: extreme ρ and
# a time unit 1e12 times shorter either solve to the scene's answer or exit 1.
add_test(NAME cli.no_false_success_at_any_rho
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/cli/no_false_success.sh ${EQHB_CLI} ${PROJECT_SOURCE_DIR}/problems)
# NLvib's cantilever in SI units sweeps its whole range on the scale-free ρ.
add_test(NAME cli.cantilever_si_sweeps_on_defaults
         COMMAND ${EXPECT_EXIT} 0 "53 points, 0 failed"
                 ${EQHB_CLI} sweep ${PROJECT_SOURCE_DIR}/problems/cantilever-friction-si.toml --step 5 --quiet)
# A given ρ far from the scale-free one is named when the solve fails.
add_test(NAME cli.badly_scaled_rho_is_named
         COMMAND ${EXPECT_EXIT} 1 "law\\[0\\] \\(coulomb-1d\\): rho = 1e-20 is .* times the scale-free rho"
                 ${EQHB_CLI} solve ${PROJECT_SOURCE_DIR}/problems/friction-1d.toml --set law[0].rho=1e-20)

# The default path: a failed solve or sweep point gets the fallback steps
# (cold start, full system, another backend) before it is given up.
add_test(NAME cli.fallback_unknown_step
         COMMAND ${EXPECT_EXIT} 2 "--fallback = cold,newton-deluxe: has an unknown step newton-deluxe"
                 ${EQHB_CLI} solve ${SCENE} --fallback cold,newton-deluxe)
add_test(NAME cli.fallback_unknown_full_system_backend
         COMMAND ${EXPECT_EXIT} 2 "--fallback = full:nonsense: has an unknown step full:nonsense"
                 ${EQHB_CLI} solve ${SCENE} --fallback full:nonsense)
add_test(NAME cli.fallback_empty_step
         COMMAND ${EXPECT_EXIT} 2 "--fallback = cold,,full: has an empty step"
                 ${EQHB_CLI} sweep ${SCENE} --fallback cold,,full)
add_test(NAME cli.fallback_repeated_step
         COMMAND ${EXPECT_EXIT} 2 "--fallback = full,full: names full twice"
                 ${EQHB_CLI} solve ${SCENE} --fallback full,full)
# Past their folds, Duffing's and the contact scene's sequential sweeps lose
# points from the previous point's start; the cold start finds them.
foreach(scene duffing contact cubic damper contact-friction-2d)
  add_test(NAME cli.${scene}_sequential_sweep_is_complete
           COMMAND ${EXPECT_EXIT} 0 "points, 0 failed"
                   ${EQHB_CLI} sweep ${PROJECT_SOURCE_DIR}/problems/${scene}.toml --quiet)
endforeach()
add_test(NAME cli.duffing_sweep_without_fallback_loses_points
         COMMAND ${EXPECT_EXIT} 1 "101 points, 9 failed"
                 ${EQHB_CLI} sweep ${PROJECT_SOURCE_DIR}/problems/duffing.toml --fallback none --quiet)
if(EQHB_WITH_IPOPT)
  # cubic at omega = 0.8 from rest: the own dogleg, the full system and the
  # cold start fail; the default's last step, Ipopt's least squares, solves it.
  add_test(NAME cli.cubic_default_path_takes_the_backup
           COMMAND ${EXPECT_EXIT} 0 "fallback: full \\(dogleg: [a-z_]+ after [0-9]+ iterations\\), ipopt-ls \\(ipopt-ls: converged\\)"
                   ${EQHB_CLI} solve ${PROJECT_SOURCE_DIR}/problems/cubic.toml --omega 0.8)
  add_test(NAME cli.cubic_without_fallback_fails
           COMMAND ${EXPECT_EXIT} 1 "did not converge"
                   ${EQHB_CLI} solve ${PROJECT_SOURCE_DIR}/problems/cubic.toml --omega 0.8 --fallback none)
endif()
if(EQHB_WITH_CERES)
  # The damper at omega = 1.3, H = 15: the own dogleg stalls on both systems,
  # Ceres' LM on the condensed one; full:ceres-lm, LM on the full system, solves it.
  add_test(NAME cli.damper_full_system_backend_step
           COMMAND ${EXPECT_EXIT} 0 "fallback: full \\(dogleg: [a-z_]+ after [0-9]+ iterations\\), full:ceres-lm \\(ceres-lm: converged\\)"
                   ${EQHB_CLI} solve ${PROJECT_SOURCE_DIR}/problems/damper.toml --omega 1.3 --harmonics 15
                   --fallback full,full:ceres-lm)
endif()
# contact at omega = 0.5 on H = 40: every step before it stalls at a local
# minimum of |g|; the chain's last step, the forcing homotopy, solves it.
add_test(NAME cli.contact_h40_default_path_takes_the_forcing_homotopy
         COMMAND ${EXPECT_EXIT} 0 "forcing \\(dogleg: converged\\); the result above is forcing's"
                 ${EQHB_CLI} solve ${PROJECT_SOURCE_DIR}/problems/contact.toml --omega 0.5 --harmonics 40)
# penalty-contact at omega = 0.7, below its hardening peak: every step before
# it stalls (|g| 0.45); the chain's last step, continuation in omega, solves it.
add_test(NAME cli.penalty_contact_default_path_takes_omega_continuation
         COMMAND ${EXPECT_EXIT} 0 "omega \\(dogleg: converged; [^)]*from omega = [0-9.]+ in [0-9]+ steps\\); the result above is omega's"
                 ${EQHB_CLI} solve ${PROJECT_SOURCE_DIR}/problems/penalty-contact.toml --omega 0.7)
add_test(NAME cli.penalty_contact_without_omega_continuation_fails
         COMMAND ${EXPECT_EXIT} 1 "did not converge"
                 ${EQHB_CLI} solve ${PROJECT_SOURCE_DIR}/problems/penalty-contact.toml --omega 0.7
                 --fallback cold,full,condensed,forcing)

# Field suite (problems/field/, bench/field_suite.py): the sequential sweep of
# each field scene on eqhb's defaults (own dogleg, 101 points over its range)
# covers its range with every point converged.
set(FIELD ${PROJECT_SOURCE_DIR}/problems/field)
add_test(NAME field.sequential_sweeps_complete
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/field_sweeps.sh ${EQHB_CLI}
                 ${FIELD}/den-hartog-coulomb.toml
                 ${FIELD}/nlvib-08-cantilever-friction-si.toml
                 ${FIELD}/nlvib-08-advanced-cantilever-friction.toml
                 ${FIELD}/nlvib-01-duffing.toml
                 ${FIELD}/nlvib-02-2dof-cubic.toml
                 ${FIELD}/nlvib-02-2dof-cubic-relative.toml
                 ${FIELD}/nlvib-07-grounded-jenkins-cubic.toml
                 ${FIELD}/nlvib-07-multiple-nonlinearities.toml
                 ${FIELD}/tmdsimpy-sdof-duffing.toml
                 ${FIELD}/tmdsimpy-2dof-duffing.toml
                 ${FIELD}/tmdsimpy-2dof-elastic-dry-friction.toml
                 ${FIELD}/tmdsimpy-sdof-jenkins-f33.toml
                 ${FIELD}/tmdsimpy-sdof-jenkins-f38.toml)
set_tests_properties(field.sequential_sweeps_complete PROPERTIES TIMEOUT 90)
# Points that fail from the point before them and from the fallbacks, found
# from the next grid point backwards: the softening Duffing oscillator lost
# omega = 0.985 (the upper branch at its jump), NLvib's example 03 seven
# points between 0.60 and 0.65 as a rigid wall and twelve between 0.62 and
# 0.653 as its source poses it (penalty spring, stiffness 100).
add_test(NAME field.sequential_sweeps_from_ahead
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/field_sweeps.sh ${EQHB_CLI}
                 ${FIELD}/tmdsimpy-softening-duffing.toml
                 ${FIELD}/nlvib-03-unilateral-wall.toml
                 ${FIELD}/nlvib-03-unilateral-spring.toml)
set_tests_properties(field.sequential_sweeps_from_ahead PROPERTIES TIMEOUT 300)
# A scene's N is chosen for its own H: --harmonics above it keeps the samples
# per period of the highest harmonic (Duffing's 29 samples for 7 harmonics
# become 166 for 40; friction-1d's 1024 for 10 odd harmonics 4258 for 40),
# below it keeps the scene's N, and an explicit --samples below 2 k_max + 1
# is refused.
add_test(NAME cli.harmonics_raise_too_few_samples
         COMMAND ${EXPECT_EXIT} 0 "\"samples\": ?166"
                 ${EQHB_CLI} solve ${PROJECT_SOURCE_DIR}/problems/duffing.toml --harmonics 40 --json)
add_test(NAME cli.harmonics_keep_samples_per_period
         COMMAND ${EXPECT_EXIT} 0 "\"samples\": ?4258"
                 ${EQHB_CLI} solve ${SCENE} --harmonics 40 --json)
add_test(NAME cli.fewer_harmonics_keep_the_scene_samples
         COMMAND ${EXPECT_EXIT} 0 "\"samples\": ?1024"
                 ${EQHB_CLI} solve ${SCENE} --harmonics 5 --json)
add_test(NAME cli.given_samples_too_few_for_harmonics
         COMMAND ${EXPECT_EXIT} 2 "harmonic_balance.samples = 50: must be >= 2 k_max . 1 = 81"
                 ${EQHB_CLI} solve ${PROJECT_SOURCE_DIR}/problems/duffing.toml --harmonics 40 --samples 50)
