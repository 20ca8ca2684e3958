// SNARESIM_VECTOR_TARGET's choice (VectorTarget.h) for any processor: the name it gives where
// the processor has it, the widest the processor has and one line where it lacks it or the
// name is unknown. The renders on each target are held to the goldens in Tests/Golden.

#include "VectorTarget.h"

#include <catch2/catch.hpp>

#include <cstdlib>

using namespace snaresim;

TEST_CASE("the vector target is the one asked for where the processor has it, else the widest it has", "[vector]")
{
    const VectorTarget all[] { VectorTarget::baseline, VectorTarget::avx2, VectorTarget::avx512 };
    for (const auto widest : all)
    {
        INFO("widest " << vectorTargetName(widest));
        for (const char* none : { (const char*) nullptr, "" })
        {
            const auto c = chooseVectorTarget(none, widest);
            CHECK(c.target == widest);
            CHECK(c.warning.empty());
        }
        for (const auto asked : all)
        {
            const std::string name(vectorTargetName(asked));
            INFO("asked " << name);
            const auto c = chooseVectorTarget(name.c_str(), widest);
            if (asked <= widest)
            {
                CHECK(c.target == asked);
                CHECK(c.warning.empty());
            }
            else
            {
                CHECK(c.target == widest);
                CHECK(c.warning.find("SNARESIM_VECTOR_TARGET=" + name) == 0);
                CHECK(c.warning.find("using " + std::string(vectorTargetName(widest))) != std::string::npos);
                CHECK(c.warning.find('\n') == std::string::npos);
            }
        }
        const auto unknown = chooseVectorTarget("AVX2", widest); // names are lower case
        CHECK(unknown.target == widest);
        CHECK(unknown.warning.find("not one of baseline, avx2, avx512") != std::string::npos);
    }
}

TEST_CASE("the vector target in force is the one SNARESIM_VECTOR_TARGET and this processor choose", "[vector]")
{
    // chosen once, when the engine is loaded, from the environment this test runs in
    CHECK(vectorTarget() == chooseVectorTarget(std::getenv("SNARESIM_VECTOR_TARGET"), widestVectorTarget()).target);
}
