# Instruction sets: the width-dependent code compiled once per set in RAYLANE_ISAS, each copy in
# its namespace (raylane::isa_sse42, isa_avx2, isa_avx512), the rest for the baseline
# (RAYLANE_ARCH). Included by the top-level CMakeLists.txt after raylane_flags.
#
#   raylane_baseline(target)                 the baseline's -march
#   raylane_isa_target(target isa)           a set's -march and namespace (a test or benchmark
#                                            program compiled for one set)
#   raylane_isa_objects(name sources...)     the sources once per set, as one relocatable object
#                                            per set in ${name}_OBJECTS (cmake/isa_object.sh)
#   raylane_isa_namespace(isa variable)      isa_sse42, isa_avx2 or isa_avx512

set(raylane_known_isas sse4.2 avx2 avx512)
foreach(isa ${RAYLANE_ISAS})
  if(NOT isa IN_LIST raylane_known_isas)
    message(FATAL_ERROR "RAYLANE_ISAS: unknown instruction set '${isa}' (sets: sse4.2, avx2, avx512)")
  endif()
endforeach()
if(NOT RAYLANE_ISAS)
  message(FATAL_ERROR "RAYLANE_ISAS is empty: name at least one of sse4.2, avx2, avx512")
endif()

# -march of each set: the x86-64 psABI levels, which core/isa.cpp tests feature by feature
set(raylane_arch_sse4.2 x86-64-v2)
set(raylane_arch_avx2 x86-64-v3)
set(raylane_arch_avx512 x86-64-v4)
set(raylane_ns_sse4.2 isa_sse42)
set(raylane_ns_avx2 isa_avx2)
set(raylane_ns_avx512 isa_avx512)
set(raylane_enum_sse4.2 sse42)
set(raylane_enum_avx2 avx2)
set(raylane_enum_avx512 avx512)

if(RAYLANE_NATIVE)
  # the widest set this machine's compiler targets with -march=native, alone, compiled native
  execute_process(COMMAND ${CMAKE_CXX_COMPILER} -march=native -dM -E -x c++ /dev/null
    OUTPUT_VARIABLE native_macros ERROR_QUIET)
  if(native_macros MATCHES "__AVX512BW__" AND native_macros MATCHES "__AVX512VL__")
    set(native_isa avx512)
  elseif(native_macros MATCHES "__AVX2__" AND native_macros MATCHES "__FMA__")
    set(native_isa avx2)
  else()
    set(native_isa sse4.2)
  endif()
  set(RAYLANE_ISAS ${native_isa})
  set(RAYLANE_ARCH native)
  set(raylane_arch_${native_isa} native)
  message(STATUS "RAYLANE_NATIVE: -march=native, instruction set ${native_isa} only")
endif()

foreach(isa ${raylane_known_isas})
  string(TOUPPER "${raylane_enum_${isa}}" upper)
  if(isa IN_LIST RAYLANE_ISAS)
    target_compile_definitions(raylane_flags INTERFACE RAYLANE_HAS_${upper}=1)
  else()
    target_compile_definitions(raylane_flags INTERFACE RAYLANE_HAS_${upper}=0)
  endif()
endforeach()

function(raylane_isa_namespace isa variable)
  set(${variable} ${raylane_ns_${isa}} PARENT_SCOPE)
endfunction()

function(raylane_baseline target)
  target_compile_options(${target} PRIVATE -march=${RAYLANE_ARCH})
endfunction()

function(raylane_isa_target target isa)
  target_compile_options(${target} PRIVATE -march=${raylane_arch_${isa}})
  target_compile_definitions(${target} PRIVATE RAYLANE_ISA_NS=${raylane_ns_${isa}}
    RAYLANE_ISA_ENUM=${raylane_enum_${isa}})
endfunction()

# The object libraries made, for settings that apply to all of them (position-independent code
# for the Python module).
set_property(GLOBAL PROPERTY RAYLANE_ISA_OBJECT_LIBRARIES "")

# GNU binutils for the partial link (ld.bfd: --force-group-allocation; Clang's toolchain may name
# lld as CMAKE_LINKER) and the symbol edits
find_program(RAYLANE_LD_BFD NAMES ld.bfd ld REQUIRED)
find_program(RAYLANE_OBJCOPY NAMES objcopy REQUIRED)
find_program(RAYLANE_NM NAMES nm REQUIRED)
find_program(RAYLANE_OBJDUMP NAMES objdump REQUIRED)

function(raylane_isa_objects name)
  set(outputs "")
  if(RAYLANE_SANITIZE)
    set(init_rule allow-init)  # the sanitizers register each object's globals at start-up
  else()
    set(init_rule no-init)
  endif()
  foreach(isa ${RAYLANE_ISAS})
    set(ns ${raylane_ns_${isa}})
    set(lib ${name}_${ns})
    add_library(${lib} OBJECT ${ARGN})
    target_link_libraries(${lib} PRIVATE raylane_flags)
    raylane_isa_target(${lib} ${isa})
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
      # static variables of inline functions as weak symbols, which isa_object.sh can make
      # local, instead of GNU-unique ones, which objcopy leaves global
      target_compile_options(${lib} PRIVATE -fno-gnu-unique)
    endif()
    set_property(GLOBAL APPEND PROPERTY RAYLANE_ISA_OBJECT_LIBRARIES ${lib})
    set(out ${CMAKE_CURRENT_BINARY_DIR}/${lib}.o)
    add_custom_command(OUTPUT ${out}
      COMMAND sh ${CMAKE_SOURCE_DIR}/cmake/isa_object.sh ${RAYLANE_LD_BFD} ${RAYLANE_OBJCOPY}
              ${RAYLANE_NM} ${RAYLANE_OBJDUMP} ${ns} ${init_rule} ${out} "$<TARGET_OBJECTS:${lib}>"
      DEPENDS ${lib} "$<TARGET_OBJECTS:${lib}>" ${CMAKE_SOURCE_DIR}/cmake/isa_object.sh
      COMMENT "Linking the ${isa} objects of ${name} (only raylane::${ns} stays global)"
      COMMAND_EXPAND_LISTS VERBATIM)
    list(APPEND outputs ${out})
  endforeach()
  set(${name}_OBJECTS ${outputs} PARENT_SCOPE)
endfunction()
