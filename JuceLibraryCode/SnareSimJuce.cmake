# SnareSim's JUCE configuration: the module flags shared by every target that compiles JUCE
# module sources (the plugin's shared code and the plugin tests' host library).
# Included by the root CMakeLists.txt after find_package(JUCE). No JUCE source lives in the repo:
# the modules come from Debian's juce-modules-source (/usr/share/juce/modules).

option(SNARESIM_JUCE_LTO
    "Link-time optimisation for the JUCE targets (slow: every executable and plug-in that links the shared code then re-optimises JUCE at link time)"
    OFF)

# The plug-in's LV2 URI: passed to juce_add_plugin and, because Debian's JUCE packaging is
# known to lose that argument, also defined as JucePlugin_LV2URI on the shared code.
set(SNARESIM_LV2_URI "https://snaresim.org/plugins/snaresim"
    CACHE STRING "LV2 URI of the SnareSim plug-in")

add_library(snaresim_juce_config INTERFACE)
add_library(snaresim::juce_config ALIAS snaresim_juce_config)

target_compile_definitions(snaresim_juce_config INTERFACE
    # Debian builds JUCE against the system FLAC / Ogg Vorbis but does not link them:
    # leaving these on makes the link fail. The product needs WAV only.
    JUCE_USE_FLAC=0
    JUCE_USE_OGGVORBIS=0
    JUCE_USE_MP3AUDIOFORMAT=0
    JUCE_USE_LAME_AUDIO_FORMAT=0
    JUCE_USE_WINDOWS_MEDIA_FORMAT=0
    # No network, no web view (no libcurl / webkit2gtk at link time).
    JUCE_WEB_BROWSER=0
    JUCE_USE_CURL=0
    JUCE_LOAD_CURL_SYMBOLS_LAZILY=0
    JUCE_DISPLAY_SPLASH_SCREEN=0
    JUCE_VST3_CAN_REPLACE_VST2=0
    JUCE_STRICT_REFCOUNTEDPOINTER=1
    # Audio devices for the standalone application: ALSA and JACK (JACK is loaded at run time).
    JUCE_ALSA=1
    JUCE_JACK=1
)

target_link_libraries(snaresim_juce_config INTERFACE
    juce::juce_recommended_config_flags
    juce::juce_recommended_warning_flags)

# GCC 12 reports a false positive in JUCE's ListenerList (juce_ListenerList.h) in every module.
target_compile_options(snaresim_juce_config INTERFACE
    $<$<CXX_COMPILER_ID:GNU>:-Wno-dangling-pointer>)

if(SNARESIM_JUCE_LTO)
    target_link_libraries(snaresim_juce_config INTERFACE juce::juce_recommended_lto_flags)
endif()

# snaresim_add_juce_library(LIBRARY lib INTERFACE face MODULES module... [DEFINITIONS def...] [SOURCES src...])
# A static library `lib` that compiles these JUCE modules (and the sources) once, PRIVATE, with
# SnareSim's module flags, hidden visibility and Debian's system PNG / JPEG decoders, and an
# INTERFACE target `face` that re-exports their include directories and compile definitions:
# linking `face` compiles no JUCE source again.
function(snaresim_add_juce_library)
    cmake_parse_arguments(arg "" "LIBRARY;INTERFACE" "MODULES;DEFINITIONS;SOURCES" ${ARGN})
    add_library(${arg_LIBRARY} STATIC ${arg_SOURCES})
    target_compile_definitions(${arg_LIBRARY} PRIVATE ${arg_DEFINITIONS})
    target_link_libraries(${arg_LIBRARY} PRIVATE snaresim_juce_config ${arg_MODULES})
    if(TARGET juce::pkgconfig_JUCE_IMG_LINUX_DEPS)
        target_link_libraries(${arg_LIBRARY} PRIVATE juce::pkgconfig_JUCE_IMG_LINUX_DEPS)
    endif()
    set_target_properties(${arg_LIBRARY} PROPERTIES
        VISIBILITY_INLINES_HIDDEN TRUE
        CXX_VISIBILITY_PRESET hidden
        C_VISIBILITY_PRESET hidden)

    add_library(${arg_INTERFACE} INTERFACE)
    target_link_libraries(${arg_INTERFACE} INTERFACE ${arg_LIBRARY})
    target_include_directories(${arg_INTERFACE} SYSTEM INTERFACE
        $<TARGET_PROPERTY:${arg_LIBRARY},INCLUDE_DIRECTORIES>)
    target_compile_definitions(${arg_INTERFACE} INTERFACE
        $<TARGET_GENEX_EVAL:${arg_LIBRARY},$<TARGET_PROPERTY:${arg_LIBRARY},COMPILE_DEFINITIONS>>)
    target_compile_features(${arg_INTERFACE} INTERFACE cxx_std_20)
endfunction()
