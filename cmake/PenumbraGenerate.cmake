# PenumbraGenerate.cmake — emit Penumbra's shaders at build time (README.md, "Build-time generation").
#
#   penumbra_generate_shaders(<target> OUT_DIR <dir>
#       [NAME <name>]                      # a second call on <target>: defines PENUMBRA_SHADER_DIR_<NAME>
#       [TECHNIQUE <t>] [PROFILE <p>] [SLICES <n>] [RESOLUTION <r>] [FILTER <f>] ...   # every penumbra-gen flag
#       [NO_FADE] [NO_ROTATION] [ALPHA_TEST] [SOLID_CASTERS] [IRRADIANCE_WINDOW] ...  # every penumbra-gen switch
#       [CONFIG <file.json>] [FLAGS <penumbra-gen flags>...] [VALIDATE]
#       [FILES_VARIABLE <var>])
#
# Every flag of `penumbra-gen --help` is a keyword: its name without the dashes, upper case, '-'
# as '_' (--slice-placement adaptive → SLICE_PLACEMENT adaptive, --no-rotation → NO_ROTATION),
# except --target, which is TARGET_API. penumbra_generate_flags() lists them; tests/generate/ checks them
# against the flags penumbra-gen accepts. FLAGS passes further flags through unchanged; CONFIG
# reads a JSON configuration (keywords override it). Values are checked when the shaders are
# generated, with penumbra-gen's messages.
#
# Runs penumbra-gen when the generator or the options change, writing the shaders and
# <dir>/layout.json, makes <target> depend on them and defines PENUMBRA_SHADER_DIR="<dir>" in
# <target> (PENUMBRA_SHADER_DIR_<NAME> with NAME, so that one target can take several
# configurations). A relative OUT_DIR is taken from the current binary directory. When the
# generator is found at configure time (an installed package), it is run once then to learn the
# file names: every generated file is an OUTPUT of the command (and is listed in FILES_VARIABLE),
# and a bad value stops the configure step with penumbra-gen's message. In the source tree
# (add_subdirectory with PENUMBRA_BUILD_GENERATOR) penumbra-gen is not built yet at configure time,
# so the OUTPUT is <dir>/layout.json, which lists the files.
# When the options change, <dir> holds exactly the files the new layout.json lists: penumbra-gen
# removes the files of the previous configuration (no stale *.frag), all or nothing.
include_guard(GLOBAL)
# The functions keep these policies (IN_LIST, cmake_path) whatever the including project asks for.
cmake_policy(PUSH)
cmake_policy(VERSION 3.20)

# penumbra-gen's flags that take a value, and its switches, which become keywords. The lists are
# written from the table of configuration fields (test "generate_flags" keeps them so; tests/generate/
# checks them against the flags penumbra-gen accepts). A function, not variables: include_guard(GLOBAL)
# would hide variables from sibling directories.
function(penumbra_generate_flags value_var switch_var)
    # generated from the table of configuration fields by
    # penumbra-config-schema --write-cmake cmake/PenumbraGenerate.cmake
    set(${value_var}
        --technique --profile --light --target --slices --resolution --filter --fusion --packing
        --tangent-clip-offset --fade-ramp --slice-placement --level-bound --level-format --level-reduction
        --prefilter-stage --shadow-resolution --shadow-bias --shadow-slope-bias --shadow-normal-offset
        --pcf-pattern --pcf-grid --pcf-taps --pcf-radius --pcss-blockers --pcss-filter --pcss-max-texels
        --oim-resolution --oim-intervals --oim-samples --erosion-radius --erosion-edge-threshold
        --erosion-search-taps --erosion-blur-taps --evsm-positive-exponent --evsm-negative-exponent
        --evsm-bleeding --evsm-variance-bias --evsm-blur-fraction --evsm-blur-taps --evsm-max-blur --smrt-rays
        --smrt-samples --smrt-extrapolate-slope --smrt-max-slope-bias --smrt-texel-dither --smrt-frame
        PARENT_SCOPE)
    set(${switch_var}
        --alpha-test --no-alpha-test --no-leak-fix --no-fade --tangent-clip --no-tangent-clip
        --no-clip-footprint --solid-casters --irradiance-window --no-irradiance-window --irradiance-quadrants
        --no-irradiance-quadrants --near-field --no-near-field --no-receiver-plane-bias --no-rotation
        --validate
        PARENT_SCOPE)
    # end of the generated flags
endfunction()

# The keyword of a flag: --slice-placement → SLICE_PLACEMENT; --target → TARGET_API (the first
# argument is already a target).
function(penumbra_generate_keyword flag out_var)
    if(flag STREQUAL "--target")
        set(${out_var} TARGET_API PARENT_SCOPE)
        return()
    endif()
    string(REGEX REPLACE "^--" "" keyword "${flag}")
    string(REPLACE "-" "_" keyword "${keyword}")
    string(TOUPPER "${keyword}" keyword)
    set(${out_var} ${keyword} PARENT_SCOPE)
endfunction()

function(penumbra_generate_shaders target)
    penumbra_generate_flags(value_flags switch_flags)
    set(value_keywords "")
    foreach(flag IN LISTS value_flags)
        penumbra_generate_keyword(${flag} keyword)
        list(APPEND value_keywords ${keyword})
    endforeach()
    set(switch_keywords "")
    foreach(flag IN LISTS switch_flags)
        penumbra_generate_keyword(${flag} keyword)
        list(APPEND switch_keywords ${keyword})
    endforeach()
    cmake_parse_arguments(PARSE_ARGV 1 arg
        "${switch_keywords}"
        "OUT_DIR;NAME;CONFIG;FILES_VARIABLE;${value_keywords}"
        "FLAGS")
    set(where "penumbra_generate_shaders(${target})")
    if(arg_UNPARSED_ARGUMENTS)
        string(JOIN " " unknown ${arg_UNPARSED_ARGUMENTS})
        string(JOIN ", " allowed OUT_DIR NAME CONFIG FLAGS FILES_VARIABLE ${value_keywords} ${switch_keywords})
        message(FATAL_ERROR "${where}: unknown arguments '${unknown}'; allowed: ${allowed}")
    endif()
    foreach(keyword IN LISTS arg_KEYWORDS_MISSING_VALUES)
        if(NOT keyword STREQUAL "FLAGS")
            message(FATAL_ERROR "${where}: ${keyword} needs a value")
        endif()
    endforeach()
    if(NOT TARGET ${target})
        message(FATAL_ERROR "${where}: '${target}' is not a target")
    endif()
    if(NOT arg_OUT_DIR)
        message(FATAL_ERROR "${where}: OUT_DIR is required")
    endif()

    # The installed package exports penumbra::penumbra-gen; in-tree it is an alias of penumbra-gen.
    if(TARGET penumbra::penumbra-gen)
        set(generator penumbra::penumbra-gen)
    elseif(TARGET penumbra-gen)
        set(generator penumbra-gen)
    else()
        message(FATAL_ERROR "${where}: no penumbra-gen target; build Penumbra with PENUMBRA_BUILD_GENERATOR=ON "
            "(as the top-level project, or -DPENUMBRA_BUILD_GENERATOR=ON as a subproject)")
    endif()

    cmake_path(ABSOLUTE_PATH arg_OUT_DIR BASE_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR} NORMALIZE
        OUTPUT_VARIABLE out_dir)

    # One macro per call: PENUMBRA_SHADER_DIR, or PENUMBRA_SHADER_DIR_<NAME>.
    set(define PENUMBRA_SHADER_DIR)
    if(DEFINED arg_NAME)
        if(NOT arg_NAME MATCHES "^[A-Za-z0-9_]+$")
            message(FATAL_ERROR "${where}: NAME '${arg_NAME}'; allowed: letters, digits and '_'")
        endif()
        string(TOUPPER "${arg_NAME}" name)
        set(define PENUMBRA_SHADER_DIR_${name})
    endif()
    get_property(defines TARGET ${target} PROPERTY PENUMBRA_GENERATE_DEFINES)
    if(define IN_LIST defines)
        message(FATAL_ERROR "${where}: ${define} is already defined by an earlier call on '${target}'; "
            "give each call on a target its own NAME <name> (defines PENUMBRA_SHADER_DIR_<NAME>)")
    endif()
    get_property(out_dirs GLOBAL PROPERTY PENUMBRA_GENERATE_OUT_DIRS)
    if(out_dir IN_LIST out_dirs)
        message(FATAL_ERROR "${where}: OUT_DIR ${out_dir} is already written by another call; "
            "give each configuration its own OUT_DIR")
    endif()
    set_property(TARGET ${target} APPEND PROPERTY PENUMBRA_GENERATE_DEFINES ${define})
    set_property(GLOBAL APPEND PROPERTY PENUMBRA_GENERATE_OUT_DIRS ${out_dir})

    # Each keyword to its command-line flag, in the CLI's order.
    set(args "")
    foreach(flag IN LISTS value_flags)
        penumbra_generate_keyword(${flag} keyword)
        if(DEFINED arg_${keyword})
            list(APPEND args ${flag} ${arg_${keyword}})
        endif()
    endforeach()
    foreach(flag IN LISTS switch_flags)
        penumbra_generate_keyword(${flag} keyword)
        if(arg_${keyword} AND NOT keyword STREQUAL "VALIDATE")
            list(APPEND args ${flag})
        endif()
    endforeach()
    list(APPEND args ${arg_FLAGS})
    set(depends ${generator})
    if(arg_CONFIG)
        cmake_path(ABSOLUTE_PATH arg_CONFIG BASE_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR} NORMALIZE)
        # --config first: the keywords override the file.
        list(PREPEND args --config ${arg_CONFIG})
        list(APPEND depends ${arg_CONFIG})
    endif()
    set(run_args ${args})
    if(arg_VALIDATE)
        list(APPEND run_args --validate)
    endif()
    list(APPEND run_args --out ${out_dir})

    string(MD5 key "${out_dir}")
    string(SUBSTRING "${key}" 0 8 key)
    set(work_dir ${CMAKE_CURRENT_BINARY_DIR}/penumbra_generate/${target}_${key})

    # The file names, from the generator itself when it exists at configure time (installed).
    set(outputs ${out_dir}/layout.json)
    get_target_property(imported ${generator} IMPORTED)
    if(imported)
        get_target_property(generator_path ${generator} LOCATION)
    endif()
    if(imported AND EXISTS "${generator_path}")
        set(probe ${work_dir}/probe)
        file(REMOVE_RECURSE ${probe})
        execute_process(COMMAND ${generator_path} ${args} --out ${probe}
            RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
        if(NOT result EQUAL 0)
            string(STRIP "${output}" output)
            string(JOIN " " command ${args})
            message(FATAL_ERROR "${where}: penumbra-gen ${command}: ${output}")
        endif()
        file(READ ${probe}/layout.json layout)
        string(JSON count LENGTH "${layout}" files)
        math(EXPR last "${count} - 1")
        set(outputs "")
        foreach(i RANGE ${last})
            string(JSON file GET "${layout}" files ${i})
            list(APPEND outputs ${out_dir}/${file})
        endforeach()
        file(REMOVE_RECURSE ${probe})
        # A new generator (or configuration file) may write other files: configure again.
        set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${generator_path} ${arg_CONFIG})
    endif()

    # Makefile generators do not rerun a command whose arguments changed, so the arguments are
    # also written to a file the command depends on (file(CONFIGURE) rewrites it only on change).
    set(args_file ${work_dir}/args)
    file(CONFIGURE OUTPUT ${args_file} CONTENT "${run_args}\n")

    # The stamp marks a run that finished.
    set(stamp ${out_dir}/penumbra-gen.stamp)
    add_custom_command(
        OUTPUT ${outputs} ${stamp}
        COMMAND ${CMAKE_COMMAND} -E make_directory ${out_dir}
        COMMAND $<TARGET_FILE:${generator}> ${run_args}
        COMMAND ${CMAKE_COMMAND} -E touch ${stamp}
        DEPENDS ${depends} ${args_file}
        COMMENT "Generating Penumbra shaders in ${out_dir}"
        VERBATIM)
    add_custom_target(penumbra_shaders_${target}_${key} DEPENDS ${outputs} ${stamp})
    add_dependencies(${target} penumbra_shaders_${target}_${key})
    target_compile_definitions(${target} PRIVATE "${define}=\"${out_dir}\"")
    if(arg_FILES_VARIABLE)
        set(${arg_FILES_VARIABLE} ${outputs} PARENT_SCOPE)
    endif()
endfunction()

cmake_policy(POP)
