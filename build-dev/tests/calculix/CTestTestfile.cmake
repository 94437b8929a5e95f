# CMake generated Testfile for 
# Source directory: /work/main/tests/calculix
# Build directory: /work/main/build-dev/tests/calculix
# 
# This file includes the relevant testing commands required for 
# testing this directory and lists subdirectories to be tested as well.
add_test([=[calculix.inputs_generated]=] "/root/.pyenv/shims/python3" "-m" "pytest" "-q" "-p" "no:cacheprovider" "/work/main/tests/calculix/test_calculix.py" "-k" "test_inputs_are_generated")
set_tests_properties([=[calculix.inputs_generated]=] PROPERTIES  _BACKTRACE_TRIPLES "/work/main/tests/calculix/CMakeLists.txt;21;add_test;/work/main/tests/calculix/CMakeLists.txt;0;")
add_test([=[calculix.input_digits]=] "/root/.pyenv/shims/python3" "-m" "pytest" "-q" "-p" "no:cacheprovider" "/work/main/tests/calculix/test_input_digits.py")
set_tests_properties([=[calculix.input_digits]=] PROPERTIES  _BACKTRACE_TRIPLES "/work/main/tests/calculix/CMakeLists.txt;24;add_test;/work/main/tests/calculix/CMakeLists.txt;0;")
add_test([=[calculix.abaqus_decks]=] "/root/.pyenv/shims/python3" "-m" "pytest" "-q" "-p" "no:cacheprovider" "/work/main/tests/calculix/test_abaqus_decks.py")
set_tests_properties([=[calculix.abaqus_decks]=] PROPERTIES  _BACKTRACE_TRIPLES "/work/main/tests/calculix/CMakeLists.txt;25;add_test;/work/main/tests/calculix/CMakeLists.txt;0;")
add_test([=[calculix.drop_in]=] "/root/.pyenv/shims/python3" "/work/main/tests/calculix/run_drop_in.py")
set_tests_properties([=[calculix.drop_in]=] PROPERTIES  ENVIRONMENT "CAMCLAY9_BUILD=/work/main/build-dev;CAMCLAY9_UMAT_OBJECT=/work/main/build-dev/umat/camclay9_umat.o;CAMCLAY9_UMAT_LIBRARY=/work/main/build-dev/umat/libcamclay9.so.0.1.0" SKIP_RETURN_CODE "77" TIMEOUT "1800" _BACKTRACE_TRIPLES "/work/main/tests/calculix/CMakeLists.txt;27;add_test;/work/main/tests/calculix/CMakeLists.txt;0;")
add_test([=[calculix.same_mesh]=] "/root/.pyenv/shims/python3" "/work/main/tests/calculix/run_drop_in.py" "test_same_mesh.py")
set_tests_properties([=[calculix.same_mesh]=] PROPERTIES  ENVIRONMENT "CAMCLAY9_BUILD=/work/main/build-dev;CAMCLAY9_UMAT_OBJECT=/work/main/build-dev/umat/camclay9_umat.o;CAMCLAY9_UMAT_LIBRARY=/work/main/build-dev/umat/libcamclay9.so.0.1.0;DRIVER=/work/main/build-dev/bin/driver" SKIP_RETURN_CODE "77" TIMEOUT "600" _BACKTRACE_TRIPLES "/work/main/tests/calculix/CMakeLists.txt;31;add_test;/work/main/tests/calculix/CMakeLists.txt;0;")
