# CMake generated Testfile for 
# Source directory: /work/main/umat
# Build directory: /work/main/build-dev/umat
# 
# This file includes the relevant testing commands required for 
# testing this directory and lists subdirectories to be tested as well.
