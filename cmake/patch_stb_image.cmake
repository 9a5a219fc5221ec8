# stb_image 2.27 (Debian 12's libstb-dev) lets a corrupt JPEG's Huffman data use more bits than
# it has: the bit count goes negative and the next refill shifts a 32-bit value by 32 or more
# (undefined behaviour; found by fuzz_image, tests/fuzz/README.md). stb_image 2.28 guards every
# place that takes bits; this writes a copy of the system header with the same guards to
# ${out_dir}/stb_image.h, to be included before the system one. Any other stb version is used as
# it is. A 2.27 header that does not match below stops the configuration: the guards are needed.
function(raylane_patch_stb_image stb_dir out_dir result_var)
  file(READ "${stb_dir}/stb_image.h" source)
  if(NOT source MATCHES "stb_image - v2\\.27 ")
    set(${result_var} "" PARENT_SCOPE)
    return()
  endif()
  # each pair: the 2.27 text, and the 2.28 text with its guard
  set(old_1 "   if (j->code_bits < n) stbi__grow_buffer_unsafe(j);\n\n   sgn = j->code_buffer >> 31;")
  set(new_1 "   if (j->code_bits < n) stbi__grow_buffer_unsafe(j);\n   if (j->code_bits < n) return 0; // raylane: 2.28's guard\n\n   sgn = j->code_buffer >> 31;")
  set(old_2 "   if (j->code_bits < n) stbi__grow_buffer_unsafe(j);\n   k = stbi_lrot(j->code_buffer, n);")
  set(new_2 "   if (j->code_bits < n) stbi__grow_buffer_unsafe(j);\n   if (j->code_bits < n) return 0; // raylane: 2.28's guard\n   k = stbi_lrot(j->code_buffer, n);")
  set(old_3 "   if (j->code_bits < 1) stbi__grow_buffer_unsafe(j);\n   k = j->code_buffer;")
  set(new_3 "   if (j->code_bits < 1) stbi__grow_buffer_unsafe(j);\n   if (j->code_bits < 1) return 0; // raylane: 2.28's guard\n   k = j->code_buffer;")
  set(old_4 "         s = r & 15; // combined length\n         j->code_buffer <<= s;")
  set(new_4 "         s = r & 15; // combined length\n         if (s > j->code_bits) return stbi__err(\"bad huffman code\", \"Combined length longer than code bits available\"); // raylane: 2.28's guard\n         j->code_buffer <<= s;")
  set(old_5 "            s = r & 15; // combined length\n            j->code_buffer <<= s;")
  set(new_5 "            s = r & 15; // combined length\n            if (s > j->code_bits) return stbi__err(\"bad huffman code\", \"Combined length longer than code bits available\"); // raylane: 2.28's guard\n            j->code_buffer <<= s;")
  foreach(i RANGE 1 5)
    string(FIND "${source}" "${old_${i}}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "stb_image 2.27 at ${stb_dir} does not have the text guard ${i} replaces "
                          "(cmake/patch_stb_image.cmake)")
    endif()
    string(REPLACE "${old_${i}}" "${new_${i}}" source "${source}")
  endforeach()
  file(CONFIGURE OUTPUT "${out_dir}/stb_image.h" CONTENT "${source}" @ONLY)
  set(${result_var} "${out_dir}" PARENT_SCOPE)
endfunction()
