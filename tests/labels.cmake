# Read by CTest (not CMake) after the gtest-discovered tests are added: tests/CMakeLists.txt
# appends a generated file that includes this one and calls rigid_label_tests once per test
# executable (TEST_INCLUDE_FILES). Labels set here may be lists, which gtest_discover_tests's
# PROPERTIES cannot express.

# The long physics runs (each over ~6 s of a Release build, most far more): label `long`, left out
# of `bash setup.sh test` (CI) and run by `bash setup.sh long` (ctest -L long). Each feature they
# check keeps a short case in CI:
#  - the 20 s stands of the three multi-block stacks: the two-piece rock, the block against a
#    face and the single rocks stand for 20 s in CI, and the stability suite has a five-block
#    stack against a wall;
#  - the two slow tilt tests (closed form g tan(alpha) at K = 1e10, irregular rock stiffening):
#    TiltTest.ModelAgainstAWallStandsWhenPushedIntoIt and StaticToppling stay;
#  - the 1e10-stiffness one-sine pulse: the three K = 1e8 HousnerPulse periods stay.
set(rigid_long_tests
    [[^Analogues/RockAnalogue\.LoadsSettlesAndStandsStillFor20Seconds/"(three_stack_wedge|five_stack_wall|four_stack_unstable_pedestal)"$]]
    [[^TiltTest\.(RectangularBlockTopplesAtGTanAlpha|IrregularRockApproachesRigidStaticsAsContactsStiffen)$]]
    [[^Periods/HousnerPulse\.OneSineThresholdWithinTenPercentOf2DModel/T500ms_K1e10( |$)]])

# In the sanitizer subset's executables but not under the sanitizers (label `sanitize` withheld;
# both still run in the Release suite): the two stability cases that are longer runs of code the
# other eleven cover (the 300 s run: the same stepping for longer; 10,000 facets: the hull and contact code of the sliver and
# nearly-coplanar cases, bigger). Under ASan+UBSan these two alone took 9 min of CPU here.
set(rigid_unsanitized_tests
    [[^Stability\.(ThreeHundredSecondRun|DegenerateMeshTenThousandFacets)$]])

# (CMake 3.25 keeps gtest's "  # GetParam() = ..." comment in the names of tests whose parameter
# it cannot print, hence "( |$)" rather than "$" where that happens.)

# rigid_label_tests(LIST LABEL SANITIZE): the tests named in the variable LIST (an executable's
# TEST_LIST, absent when it was not built) get LABEL, plus `long` when they match
# rigid_long_tests, else `sanitize` when SANITIZE is 1 and the test is not in
# rigid_unsanitized_tests
function(rigid_label_tests list label sanitize)
  foreach(test IN LISTS ${list})
    set(labels ${label})
    set(long 0)
    foreach(pattern IN LISTS rigid_long_tests)
      if(test MATCHES "${pattern}")
        set(long 1)
      endif()
    endforeach()
    set(instrumented ${sanitize})
    foreach(pattern IN LISTS rigid_unsanitized_tests)
      if(test MATCHES "${pattern}")
        set(instrumented 0)
      endif()
    endforeach()
    if(long)
      list(APPEND labels long)
    elseif(instrumented)
      list(APPEND labels sanitize)
    endif()
    set_tests_properties("${test}" PROPERTIES LABELS "${labels}")
  endforeach()
endfunction()
