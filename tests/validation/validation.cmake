# Structure-only validation: every case folder with a reference.yaml becomes a ctest test that runs
# `fsi validate` against its independent reference (analytic, published, or conservation law).
file(GLOB FSI_VALIDATION_CASES LIST_DIRECTORIES true ${PROJECT_SOURCE_DIR}/cases/structure/*)
foreach(case_dir ${FSI_VALIDATION_CASES})
  if(EXISTS ${case_dir}/reference.yaml)
    get_filename_component(case_name ${case_dir} NAME)
    add_test(NAME validation.${case_name}
             COMMAND fsi validate ${case_dir} --quiet --out ${PROJECT_BINARY_DIR}/validation/${case_name})
    set_tests_properties(validation.${case_name} PROPERTIES TIMEOUT 1200 LABELS validation)
  endif()
endforeach()

# The parafoil's structure resolution study: the mean stress and the mid-cell resultant converge, the
# membrane's normal equilibrium at mid-cell approaches Young-Laplace (tests/validation/parafoil_convergence.py).
add_test(NAME validation.parafoil-convergence
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/parafoil_convergence.py $<TARGET_FILE:fsi>
                 ${PROJECT_BINARY_DIR}/validation/parafoil-convergence)
set_tests_properties(validation.parafoil-convergence PROPERTIES TIMEOUT 1800 LABELS validation)

# The parafoil's trailing edge after inflation: cosine chordwise spacing crumples it, half-cosine does not, and
# both carry the same load (tests/validation/parafoil_trailing_edge.py).
add_test(NAME validation.parafoil-trailing-edge
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/parafoil_trailing_edge.py $<TARGET_FILE:fsi>
                 ${PROJECT_BINARY_DIR}/validation/parafoil-trailing-edge)
set_tests_properties(validation.parafoil-trailing-edge PROPERTIES TIMEOUT 600 LABELS validation)

# The parafoil generator's row_trim against the rigid-canopy estimate: rows trimmed in proportion turn the
# inflated canopy nose-down by about trim / row spread; one row lengthened alone only slackens it
# (tests/validation/parafoil_row_trim.py, about 30 s).
add_test(NAME validation.parafoil-row-trim
         COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/parafoil_row_trim.py $<TARGET_FILE:fsi>
                 ${PROJECT_BINARY_DIR}/validation/parafoil-row-trim)
set_tests_properties(validation.parafoil-row-trim PROPERTIES TIMEOUT 600 LABELS validation)

# The round canopy's opening from line stretch at CI size (studies/roundcanopy/round_canopy_inflation.py,
# docs/ROUND_CANOPY.md "Inflation"): the peak force scales with the speed squared, falls with porosity and
# with a finite payload mass; the filling time and the opening-load factor reported (about 20 s).
add_test(NAME validation.round-canopy-trends
         COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/studies/roundcanopy/round_canopy_inflation.py
                 $<TARGET_FILE:fsi> ${PROJECT_BINARY_DIR}/validation/round-canopy-trends)
set_tests_properties(validation.round-canopy-trends PROPERTIES TIMEOUT 300 LABELS "validation;hard")
