# CMake generated Testfile for 
# Source directory: /work/wt-rtf/tools/rtf_parts
# Build directory: /work/wt-rtf/build/release/tools/rtf_parts
# 
# This file includes the relevant testing commands required for 
# testing this directory and lists subdirectories to be tested as well.
