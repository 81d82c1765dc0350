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
