# Hardens one lcm-gen C++ header in place: cmake -DHEADER=<file>.hpp -P LcmDecodeBounds.cmake
#
# lcm-gen 1.3.1's decoders trust the length fields of the bytes they decode:
#   - a variable-length array is resized to its count before anything checks that the message
#     holds that many elements: a 30-byte payload claiming 2^31 floats makes the receiver
#     allocate and zero 8 GB (or throw bad_alloc);
#   - a string's length field is used as `len - 1` after only an upper check: len = INT32_MIN
#     overflows (undefined behaviour), len = 0 asks std::string for SIZE_MAX bytes.
# Every process decodes what anyone on the multicast group sends (fuzz/lcm_*_fuzz found both),
# so each resize gets a guard that its count fits in the bytes left (every LCM element takes at
# least one byte) and each string length must be at least 1 (its terminating NUL). A decoder
# that fails a guard returns -1, which LCM and lcmtypes::Decode already treat as malformed.
# The build fails if the generated code has a form this script does not know, rather than
# leaving a decoder unguarded.
cmake_minimum_required(VERSION 3.25)
if(NOT HEADER)
  message(FATAL_ERROR "LcmDecodeBounds.cmake: set HEADER")
endif()
file(READ "${HEADER}" text)

set(id "[A-Za-z_][A-Za-z0-9_]*")
string(REGEX MATCHALL "\\.resize\\(" all_resizes "${text}")
string(REGEX MATCHALL "\n *this->${id}\\.resize\\(this->${id}\\)" simple_resizes "${text}")
string(REGEX MATCHALL "\\.assign\\(" all_assigns "${text}")
string(REGEX MATCHALL "if\\(${id} > maxlen - pos\\) return -1" string_checks "${text}")
list(LENGTH all_resizes n_resizes)
list(LENGTH simple_resizes n_simple)
list(LENGTH all_assigns n_assigns)
list(LENGTH string_checks n_checks)
if(NOT n_resizes EQUAL n_simple OR NOT n_assigns EQUAL n_checks)
  message(FATAL_ERROR "${HEADER}: lcm-gen wrote array or string decoding this script does not "
                      "know (${n_simple} of ${n_resizes} resizes, ${n_checks} of ${n_assigns} "
                      "string checks recognised): extend cmake/LcmDecodeBounds.cmake")
endif()

string(REGEX REPLACE "\n( *)(this->${id}\\.resize\\((this->${id})\\);)"
       "\n\\1if(\\3 < 0 || \\3 > maxlen - pos) return -1;  // LcmDecodeBounds.cmake\n\\1\\2"
       text "${text}")
string(REGEX REPLACE "if\\((${id}) > maxlen - pos\\) return -1;"
       "if(\\1 < 1 || \\1 > maxlen - pos) return -1;  // LcmDecodeBounds.cmake" text "${text}")
file(WRITE "${HEADER}" "${text}")
