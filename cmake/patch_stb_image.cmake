# stb_image 2.27 (Debian 12's libstb-dev) lets a corrupt JPEG's Huffman data use more bits than
# it has: the bit count goes negative and the next refill shifts a 32-bit value by 32 or more
# (undefined behaviour; found by fuzz_image, tests/fuzz/README.md). stb_image 2.28 added guards
# where bits are taken; this writes a copy of the system header with such guards (written here
# after 2.28's, not copied from it) to ${out_dir}/stb_image.h, to be included before the system
# one. Any other stb version is used as it is. A 2.27 header that does not match below stops the
# configuration: the guards are needed. The copy is rewritten only when its text changes (no
# rebuild otherwise), and CMake reconfigures when the system header changes.
function(raylane_patch_stb_image stb_dir out_dir result_var)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${stb_dir}/stb_image.h")
  file(READ "${stb_dir}/stb_image.h" source)
  if(NOT source MATCHES "stb_image - v2\\.27 ")
    set(${result_var} "" PARENT_SCOPE)
    return()
  endif()
  # each pair: the 2.27 text, and the 2.28 text with its guard
  set(old_1 "   if (j->code_bits < n) stbi__grow_buffer_unsafe(j);\n\n   sgn = j->code_buffer >> 31;")
  set(new_1 "   if (j->code_bits < n) stbi__grow_buffer_unsafe(j);\n   if (j->code_bits < n) return 0; // raylane: bit-count guard, after stb 2.28\n\n   sgn = j->code_buffer >> 31;")
  set(old_2 "   if (j->code_bits < n) stbi__grow_buffer_unsafe(j);\n   k = stbi_lrot(j->code_buffer, n);")
  set(new_2 "   if (j->code_bits < n) stbi__grow_buffer_unsafe(j);\n   if (j->code_bits < n) return 0; // raylane: bit-count guard, after stb 2.28\n   k = stbi_lrot(j->code_buffer, n);")
  set(old_3 "   if (j->code_bits < 1) stbi__grow_buffer_unsafe(j);\n   k = j->code_buffer;")
  set(new_3 "   if (j->code_bits < 1) stbi__grow_buffer_unsafe(j);\n   if (j->code_bits < 1) return 0; // raylane: bit-count guard, after stb 2.28\n   k = j->code_buffer;")
  set(old_4 "         s = r & 15; // combined length\n         j->code_buffer <<= s;")
  set(new_4 "         s = r & 15; // combined length\n         if (s > j->code_bits) return stbi__err(\"bad huffman code\", \"Combined length longer than code bits available\"); // raylane: bit-count guard, after stb 2.28\n         j->code_buffer <<= s;")
  set(old_5 "            s = r & 15; // combined length\n            j->code_buffer <<= s;")
  set(new_5 "            s = r & 15; // combined length\n            if (s > j->code_bits) return stbi__err(\"bad huffman code\", \"Combined length longer than code bits available\"); // raylane: bit-count guard, after stb 2.28\n            j->code_buffer <<= s;")
  foreach(i RANGE 1 5)
    string(FIND "${source}" "${old_${i}}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "stb_image 2.27 at ${stb_dir} does not have the text guard ${i} replaces "
                          "(cmake/patch_stb_image.cmake)")
    endif()
    string(REPLACE "${old_${i}}" "${new_${i}}" source "${source}")
  endforeach()
  # copied verbatim (file(CONFIGURE) would substitute @...@ sequences)
  file(WRITE "${out_dir}/stb_image.h.new" "${source}")
  configure_file("${out_dir}/stb_image.h.new" "${out_dir}/stb_image.h" COPYONLY)
  set(${result_var} "${out_dir}" PARENT_SCOPE)
endfunction()
