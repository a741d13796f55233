# Bad input on the command line (sizes, steps, sweeps, malformed text):
# exit status 2 and a message naming the field.
set(BAD ${CMAKE_CURRENT_SOURCE_DIR}/cli/bad)
function(eqhb_cli_expect name code pattern)
  add_test(NAME cli.${name} COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/expect_exit.sh ${code} ${pattern} ${EQHB_CLI} ${ARGN})
endfunction()
eqhb_cli_expect(element_zero_normal 2 "law\\[0\\].normal = \\[0, 0\\]: must be a nonzero, finite direction"
                solve ${BAD}/element-zero-normal.toml)
eqhb_cli_expect(refine_refuses_element_between_nodes 2 "law\\[1\\].between = .*: a cubic law between two nodes"
                solve ${PROJECT_SOURCE_DIR}/problems/field/nlvib-02-2dof-cubic-relative.toml --refine shoot)
eqhb_cli_expect(extra_argument 2 "not expected: extra" solve ${SCENE} extra)
eqhb_cli_expect(out_of_range_option 2 "--repeat: Value 0 not in range" solve ${SCENE} --repeat 0)
eqhb_cli_expect(harmonics_beyond_int 2 "--harmonics = 4294967306" solve ${SCENE} --harmonics 4294967306)
eqhb_cli_expect(harmonics_too_many 2 "harmonic_balance.harmonics = 1000000000: must be <=" solve ${SCENE} --harmonics 1000000000)
eqhb_cli_expect(samples_too_many 2 "harmonic_balance.samples = 1000000000: must be <=" solve ${SCENE} --samples 1000000000)
eqhb_cli_expect(scene_is_a_directory 2 "is a directory" solve ${PROJECT_SOURCE_DIR}/problems)
eqhb_cli_expect(invalid_utf8 2 "line 1: not valid UTF-8" solve ${BAD}/invalid-utf8.toml)
eqhb_cli_expect(deep_nesting 2 "nested deeper than 32" solve ${BAD}/deep-nesting.toml)
eqhb_cli_expect(harmonics_wrap 2 "harmonic_balance.harmonics = 4294967306: must be <=" solve ${BAD}/harmonics-wrap.toml)
eqhb_cli_expect(simulate_tiny_step 2 "step = 1e-09: gives .* steps per period" simulate ${SCENE} --step 1e-9)
eqhb_cli_expect(simulate_zero_step 2 "step = 0: must be finite and > 0" simulate ${SCENE} --step 0)
eqhb_cli_expect(simulate_nan_step 2 "step = nan: must be finite" simulate ${SCENE} --step nan)
eqhb_cli_expect(sweep_tiny_step 2 "step = 1e-12: the grid 0.1 -> 0.8 needs .* points, more than max_points = 20000" sweep ${SCENE} --step 1e-12)
eqhb_cli_expect(sweep_capped_grid 2 "step = 1e-09: the grid 0.1 -> 0.10003 needs 3000[01] points, more than max_points = 20000" sweep ${SCENE} --step 1e-9 --to 0.10003)
eqhb_cli_expect(sweep_zero_step 2 "--step = 0: must be finite and > 0" sweep ${SCENE} --step 0)
eqhb_cli_expect(sweep_nan_step 2 "--step = nan: must be finite" sweep ${SCENE} --step nan)
eqhb_cli_expect(sweep_from_without_to 2 "--to = \\(missing\\): the scene has no \\[sweep\\]" sweep ${CMAKE_CURRENT_SOURCE_DIR}/cli/no-sweep.toml --from 0.5)
eqhb_cli_expect(sweep_to_without_from 2 "--from = \\(missing\\)" sweep ${CMAKE_CURRENT_SOURCE_DIR}/cli/no-sweep.toml --to 0.5)
eqhb_cli_expect(sweep_without_range_solves 0 "stop: reached the end of the range" sweep ${CMAKE_CURRENT_SOURCE_DIR}/cli/no-sweep.toml --from 0.5 --to 0.6 --step 0.05)
eqhb_cli_expect(sweep_arclength_point_cap 1 "stop: max_points = 3 reached at omega" sweep ${SCENE} --arclength --max-points 3 --harmonics 3 --samples 64)
eqhb_cli_expect(samples_by_memory 2 "harmonics = 100000: the model .* needs about" solve ${SCENE} --harmonics 100000 --samples 400000)
eqhb_cli_expect(chain_dense_by_memory 2 "the condensed system with dense factors of A_k \\(100000 DOFs.* needs about"
                solve ${SCENE} --set structure.dofs=100000 --linear-algebra dense)
eqhb_cli_expect(negative_stiffness_matrix 2 "negative-stiffness.toml: structure.stiffness: must be positive semidefinite"
                solve ${BAD}/negative-stiffness.toml)
eqhb_cli_expect(negative_damping_matrix 2 "negative-damping.toml: structure.damping: must be positive semidefinite"
                solve ${BAD}/negative-damping.toml)
# Matrix Market files judged by their size lines before any entry is read:
# each swaps one file of a valid 2-DOF scene and is refused in milliseconds
# (before: up to minutes and gigabytes, an overflow, or std::bad_alloc).
set(MM ${BAD}/matrix-market.toml)
eqhb_cli_expect(matrix_market_valid 0 "dogleg: converged" solve ${MM})
eqhb_cli_expect(matrix_market_array_overflow 2
                "structure.mass: .*mm-array-overflow.mtx:2: a 3037000500 x 3037000500 matrix of dense array storage needs about"
                solve ${MM} --set structure.mass="mm-array-overflow.mtx" --set structure.stiffness="mm-array-overflow.mtx")
eqhb_cli_expect(matrix_market_long_load_vector 2
                "forcing\\[0\\]\\.file = .*mm-long-vector.mtx\": has 1073741823 entries, the structure has 2 DOFs"
                solve ${MM} --set forcing[0].file="mm-long-vector.mtx")
eqhb_cli_expect(matrix_market_empty_but_wide 2
                "structure.mass: .*mm-wide-empty.mtx:2: a 536870912 x 536870912 matrix of 0 entries needs about 12 GiB to read"
                solve ${MM} --set structure.mass="mm-wide-empty.mtx" --set structure.stiffness="mm-wide-empty.mtx")
eqhb_cli_expect(matrix_market_sizes_disagree 2
                "structure.stiffness = .*mm-huge-stiffness.mtx\": is 268435456 x 268435456, the mass matrix is 2 x 2 \\(sizes must agree"
                solve ${MM} --set structure.stiffness="mm-huge-stiffness.mtx")
# A line longer than the bound, written here rather than committed.
string(REPEAT "0" 5000 zeros)
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/mm-long-line.mtx
     "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n1 1 2\n2 1 -1\n2 2 ${zeros}1\n")
eqhb_cli_expect(matrix_market_long_line 2 "structure.stiffness: .*mm-long-line.mtx:5: line longer than 4096 characters"
                solve ${MM} --set structure.stiffness="${CMAKE_CURRENT_BINARY_DIR}/mm-long-line.mtx")
# 2^24 chain DOFs: the model's vectors need 11.5 GiB; refused from the sizes
# before the chain is built (before: 36 s and 5.5 GB).
eqhb_cli_expect(chain_model_by_memory 2 "structure.dofs = 16777216: the model \\(16777216 DOFs.* needs about 11.5 GiB"
                solve ${SCENE} --set structure.dofs=16777216)

# eqhb modes: a mode above the linearised structure's count (friction-1d
# stuck has one), an amplitude range <= 0 or NaN; and a backbone that runs.
eqhb_cli_expect(modes_mode_too_high 2 "mode = 2: must be in \\[1, 1\\]" modes ${SCENE} --mode 2)
eqhb_cli_expect(modes_from_zero 2 "from = 0: must be finite and > 0" modes ${SCENE} --from 0 --to 1)
eqhb_cli_expect(modes_to_nan 2 "to = nan: must be finite and > 0" modes ${SCENE} --to nan)
eqhb_cli_expect(modes_backbone_time_limit_negative 2 "--backbone-time-limit = -1: must be finite and >= 0" modes ${SCENE} --backbone-time-limit -1)
eqhb_cli_expect(modes_synthesis_without_forcing 2 "forcing = none at harmonic 1" modes ${PROJECT_SOURCE_DIR}/problems/field/modes/nlvib-05-2dof-friction-modes.toml --synthesis)
eqhb_cli_expect(modes_reversed 2 "to = 0.1: must be > from" modes ${SCENE} --from 1 --to 0.1)
eqhb_cli_expect(modes_json 0 "\"damping_ratio\": 0.0141421356" modes ${SCENE} --branch held --from 0.1 --to 1 --points 3 --json)
# friction-1d's sweep (0.1 .. 0.8) holds the free chain's mode 1 (0.618), not
# the held one (1.414): by default its mode 1 is the sliding branch.
eqhb_cli_expect(modes_default_branch 0 "\"branch\": \"sliding\"" modes ${SCENE} --points 3 --json)
eqhb_cli_expect(modes_branch_unknown 2 "--branch" modes ${SCENE} --branch stuck)
