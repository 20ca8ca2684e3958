// Loads the BUILT SnareSim VST3 and LV2 binaries through JUCE's hosting classes and plays a note.
// Catches what in-process tests cannot: unresolved symbols, a wrong LV2 URI or manifest, a
// broken bundle layout.

#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "PluginHostHarness.h"
#include "Parameters.h"

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>

#include <unistd.h>

namespace fs = std::filesystem;

namespace
{
const double sampleRate = 48000.0;
const int blockSize = 512;

juce::String canonicalPath (const char* path)
{
    std::error_code ec;
    const auto p = fs::weakly_canonical (fs::path (path), ec);
    return juce::String (ec ? std::string (path) : p.string());
}

void checkHostedPlugin (snaresim::testhost::LoadedPlugin& loaded)
{
    INFO ("load error: " << loaded.error);
    REQUIRE (loaded.instance != nullptr);

    CHECK (loaded.description.name == "SnareSim");
    CHECK (loaded.description.manufacturerName == "SnareSim");
    CHECK (loaded.description.isInstrument);

    // Every engine parameter is visible to the host, by name.
    const auto names = snaresim::testhost::parameterNames (*loaded.instance);
    for (const auto& spec : snaresim::parameterSpecs())
    {
        const juce::String name (std::string (spec.name));
        INFO ("parameter " << name << " among: " << names.joinIntoString (", "));
        CHECK (names.contains (name));
    }

    const auto rendered = snaresim::testhost::renderNote (*loaded.instance, sampleRate, blockSize, 24 * blockSize);
    CHECK (rendered.numOutputChannels >= 1);
    CHECK (rendered.allFinite);
    CHECK (rendered.peak > 1.0e-4f);
    CHECK (rendered.peak < 100.0f);
}
} // namespace

TEST_CASE ("the built VST3 loads and plays a note", "[vst3]")
{
    const auto bundle = canonicalPath (SNARESIM_TEST_VST3_BUNDLE);
    INFO ("VST3 bundle: " << bundle);
    REQUIRE (juce::File (bundle).isDirectory());
    REQUIRE (juce::File (bundle).getChildFile ("Contents/x86_64-linux/SnareSim.so").existsAsFile());

    juce::VST3PluginFormat format;
    auto loaded = snaresim::testhost::loadPlugin (format, bundle, sampleRate, blockSize);
    checkHostedPlugin (loaded);
}

TEST_CASE ("the built LV2 loads by its URI and plays a note", "[lv2]")
{
    const auto bundle = juce::File (canonicalPath (SNARESIM_TEST_LV2_BUNDLE));
    INFO ("LV2 bundle: " << bundle.getFullPathName());
    REQUIRE (bundle.isDirectory());

    // The manifest names the plug-in by the URI the project declares.
    const auto manifest = bundle.getChildFile ("manifest.ttl");
    REQUIRE (manifest.existsAsFile());
    CHECK (manifest.loadFileAsString().contains ("<" SNARESIM_TEST_LV2_URI ">"));

    // main() linked the bundle into $HOME/.lv2, where JUCE's LV2 host looks for it.
    REQUIRE (juce::File ("~/.lv2/SnareSim.lv2/manifest.ttl").existsAsFile());

    juce::LV2PluginFormat format;
    auto loaded = snaresim::testhost::loadPlugin (format, SNARESIM_TEST_LV2_URI, sampleRate, blockSize);
    checkHostedPlugin (loaded);
}

int main (int argc, char* argv[])
{
    // A private HOME with .lv2/SnareSim.lv2 -> the built bundle, set before JUCE starts: JUCE's
    // LV2 host only searches ~/.lv2, /usr/lib/lv2 and /usr/local/lib/lv2 (it ignores LV2_PATH).
    const fs::path home = fs::path (SNARESIM_TEST_HOME_ROOT) / ("home-" + std::to_string ((long) ::getpid()));
    std::error_code ec;
    fs::remove_all (home, ec);
    fs::create_directories (home / ".lv2", ec);

    const fs::path lv2Bundle (SNARESIM_TEST_LV2_BUNDLE);
    if (fs::is_directory (lv2Bundle))
        fs::create_directory_symlink (fs::canonical (lv2Bundle), home / ".lv2" / "SnareSim.lv2", ec);
    if (ec)
        std::cerr << "cannot link the LV2 bundle into " << home << ": " << ec.message() << "\n";

    ::setenv ("HOME", home.c_str(), 1);

    int result = 0;
    {
        const juce::ScopedJuceInitialiser_GUI juceInitialiser;
        result = Catch::Session().run (argc, argv);
    }

    fs::remove_all (home, ec);
    return result;
}
