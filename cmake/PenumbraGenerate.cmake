# PenumbraGenerate.cmake — emit Penumbra's shaders at build time.
#
#   penumbra_generate_shaders(<target> OUT_DIR <dir>
#       [SLICES <n>] [RESOLUTION <r>] [FILTER <f>] [FUSION <u>] [PACKING <p>] [LIGHT <l>]
#       [TARGET_API <t>] [CONFIG <file.json>] [NO_LEAK_FIX] [NO_FADE] [NO_TANGENT_CLIP] [VALIDATE])
#
# Runs penumbra-gen when the generator or the options change, writing the shaders and
# <dir>/layout.json, makes <target> depend on them and defines PENUMBRA_SHADER_DIR="<dir>" in
# <target>. Values are those of the command line (`penumbra-gen --help`); options left out keep
# the generator's defaults. A relative OUT_DIR is taken from the current binary directory.
# When the options change, <dir> holds exactly the files the new layout.json lists: penumbra-gen
# removes the files of the previous configuration (no stale *.frag), all or nothing.
include_guard(GLOBAL)

function(penumbra_generate_shaders target)
    cmake_parse_arguments(PARSE_ARGV 1 arg
        "NO_LEAK_FIX;NO_FADE;NO_TANGENT_CLIP;VALIDATE"
        "OUT_DIR;SLICES;RESOLUTION;FILTER;FUSION;PACKING;LIGHT;TARGET_API;CONFIG"
        "")
    if(arg_UNPARSED_ARGUMENTS)
        message(FATAL_ERROR "penumbra_generate_shaders: unknown arguments: ${arg_UNPARSED_ARGUMENTS}")
    endif()
    if(NOT TARGET ${target})
        message(FATAL_ERROR "penumbra_generate_shaders: '${target}' is not a target")
    endif()
    if(NOT arg_OUT_DIR)
        message(FATAL_ERROR "penumbra_generate_shaders: OUT_DIR is required")
    endif()

    # The installed package exports penumbra::penumbra-gen; in-tree it is an alias of penumbra-gen.
    if(TARGET penumbra::penumbra-gen)
        set(generator penumbra::penumbra-gen)
    elseif(TARGET penumbra-gen)
        set(generator penumbra-gen)
    else()
        message(FATAL_ERROR "penumbra_generate_shaders: no penumbra-gen target; "
            "build Penumbra with PENUMBRA_BUILD_GENERATOR=ON")
    endif()

    cmake_path(ABSOLUTE_PATH arg_OUT_DIR BASE_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR} NORMALIZE
        OUTPUT_VARIABLE out_dir)

    # Map each keyword to its command-line flag, in the CLI's order.
    set(args "")
    foreach(pair IN ITEMS SLICES:--slices RESOLUTION:--resolution FILTER:--filter FUSION:--fusion
                          PACKING:--packing LIGHT:--light TARGET_API:--target)
        string(REPLACE ":" ";" pair "${pair}")
        list(GET pair 0 keyword)
        list(GET pair 1 flag)
        if(DEFINED arg_${keyword})
            list(APPEND args ${flag} ${arg_${keyword}})
        endif()
    endforeach()
    set(depends ${generator})
    if(arg_CONFIG)
        cmake_path(ABSOLUTE_PATH arg_CONFIG BASE_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR} NORMALIZE)
        list(APPEND args --config ${arg_CONFIG})
        list(APPEND depends ${arg_CONFIG})
    endif()
    if(arg_NO_LEAK_FIX)
        list(APPEND args --no-leak-fix)
    endif()
    if(arg_NO_FADE)
        list(APPEND args --no-fade)
    endif()
    if(arg_NO_TANGENT_CLIP)
        list(APPEND args --no-tangent-clip)
    endif()
    if(arg_VALIDATE)
        list(APPEND args --validate)
    endif()
    list(APPEND args --out ${out_dir})

    # Makefile generators do not rerun a command whose arguments changed, so the arguments are
    # also written to a file the command depends on (file(CONFIGURE) rewrites it only on change).
    string(MD5 key "${out_dir}")
    string(SUBSTRING "${key}" 0 8 key)
    set(args_file ${CMAKE_CURRENT_BINARY_DIR}/penumbra_generate_${target}_${key}.args)
    file(CONFIGURE OUTPUT ${args_file} CONTENT "${args}\n")

    # layout.json names the generated files; the stamp marks a run that finished.
    set(stamp ${out_dir}/penumbra-gen.stamp)
    add_custom_command(
        OUTPUT ${out_dir}/layout.json ${stamp}
        COMMAND ${CMAKE_COMMAND} -E make_directory ${out_dir}
        COMMAND $<TARGET_FILE:${generator}> ${args}
        COMMAND ${CMAKE_COMMAND} -E touch ${stamp}
        DEPENDS ${depends} ${args_file}
        COMMENT "Generating Penumbra shaders in ${out_dir}"
        VERBATIM)
    add_custom_target(penumbra_shaders_${target}_${key} DEPENDS ${out_dir}/layout.json ${stamp})
    add_dependencies(${target} penumbra_shaders_${target}_${key})
    target_compile_definitions(${target} PRIVATE "PENUMBRA_SHADER_DIR=\"${out_dir}\"")
endfunction()
