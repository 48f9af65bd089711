// SPDX-License-Identifier: MIT
// The session's command line: each option sets its value, bad values are
// refused naming the option and what was given, names a program handles
// itself are left to it, and a program that sweeps the traversal takes
// none of its options.
#include "evaluation/session_command_line.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

using namespace occu;

namespace {

// The message take() throws for `name value`; empty when it takes them.
std::string refusal(SessionCommandLine &c, const std::string &name, const std::string &value)
{
    try {
        c.take(name, value);
    } catch (const std::invalid_argument &e) {
        return e.what();
    }
    return {};
}

}  // namespace

TEST(SessionCommandLine, TakesItsOptions)
{
    SessionCommandLine c;
    EXPECT_TRUE(c.take("--strategies", "vfc,,ou-shared"));
    EXPECT_EQ(c.strategies, (std::vector<std::string>{"vfc", "ou-shared"}));
    EXPECT_TRUE(c.take("--set", "tolerance=0.1"));
    EXPECT_TRUE(c.take("--set", "batch=8"));
    EXPECT_EQ(c.common, (std::vector<std::string>{"tolerance=0.1", "batch=8"}));
    EXPECT_TRUE(c.take("--size", "96"));
    EXPECT_TRUE(c.take("--driver", "softpipe"));
    EXPECT_TRUE(c.take("--allocator", "system"));
    EXPECT_TRUE(c.take("--batch", "7"));
    EXPECT_TRUE(c.take("--coherence", "off"));
    EXPECT_TRUE(c.take("--switch-off", "0.25"));
    EXPECT_TRUE(c.take("--databases", "/tmp/dbs"));
    EXPECT_TRUE(c.take("--make-databases", "all"));
    EXPECT_EQ(c.width, 96);
    EXPECT_EQ(c.height, 96);
    EXPECT_EQ(c.size_name(), "96");
    EXPECT_EQ(c.driver, gl::Driver::softpipe);
    EXPECT_EQ(c.allocator, AllocatorPolicy::system);
    EXPECT_EQ(c.databases, "/tmp/dbs");
    EXPECT_EQ(c.make_databases, DatabaseProvider::Makes::all);

    DatabaseProvider provider = c.database_provider();
    const SessionOptions so = c.session_options(provider);
    EXPECT_EQ(so.batch, 7u);
    EXPECT_FALSE(so.coherence);
    EXPECT_EQ(so.switch_off, 0.25);
    EXPECT_EQ(so.allocator, AllocatorPolicy::system);
    EXPECT_EQ(so.databases, &provider);
    EXPECT_EQ(provider.directory(), "/tmp/dbs");
}

TEST(SessionCommandLine, SizeIsSquareOrWidthByHeight)
{
    SessionCommandLine c;
    EXPECT_TRUE(c.take("--size", "1280x720"));
    EXPECT_EQ(c.width, 1280);
    EXPECT_EQ(c.height, 720);
    EXPECT_FLOAT_EQ(c.aspect(), 1280.0f / 720.0f);
    EXPECT_EQ(c.size_name(), "1280x720");
    EXPECT_TRUE(c.take("--size", "64"));
    EXPECT_EQ(c.width, 64);
    EXPECT_EQ(c.height, 64);
    EXPECT_TRUE(c.take("--size", "16x8192"));
    EXPECT_EQ(c.height, 8192);
}

TEST(SessionCommandLine, LookIsTheScenesUnlessGiven)
{
    SessionCommandLine c;
    EXPECT_EQ(c.look_for("city"), Look::flat);
    EXPECT_EQ(c.look_for(""), Look::flat);
    EXPECT_EQ(c.look_for("field"), Look::flat);
    EXPECT_EQ(c.look_for("pak.pk3:maps/x.bsp"), Look::scene);
    EXPECT_EQ(c.look_for("house.ifc"), Look::scene);
    EXPECT_TRUE(c.take("--look", "flat"));
    EXPECT_EQ(c.look_for("pak.pk3:maps/x.bsp"), Look::flat);
    EXPECT_TRUE(c.take("--look", "scene"));
    EXPECT_EQ(c.look_for("city"), Look::scene);
    EXPECT_EQ(refusal(c, "--look", "pretty"), "--look wants flat or scene, got 'pretty'");
}

TEST(SessionCommandLine, LeavesOtherNamesToTheProgram)
{
    SessionCommandLine c;
    EXPECT_FALSE(c.take("--route", "dense"));
    EXPECT_FALSE(c.take("--frames", "3"));
    c.traversal_options = false;
    for (const char *name : {"--batch", "--coherence", "--switch-off", "--set"})
        EXPECT_FALSE(c.take(name, "1")) << name;
    EXPECT_TRUE(c.take("--size", "64"));
    EXPECT_EQ(c.batch, 32);
    EXPECT_TRUE(c.common.empty());
}

TEST(SessionCommandLine, RefusesBadValuesNamingTheOption)
{
    SessionCommandLine c;
    c.max_size = 4096;
    EXPECT_EQ(refusal(c, "--size", "8192"), "--size wants PIXELS or WIDTHxHEIGHT, each side an integer in 16..4096, got '8192'");
    for (const char *bad : {"1280x", "x720", "1280x720x2", "1280X720", "1280x15", "8000x720", " 64x64", "64x+64", "64x6e1",
                            "-64x64", "64 x 64", "nanxnan", ""})
        EXPECT_EQ(refusal(c, "--size", bad),
                  std::string("--size wants PIXELS or WIDTHxHEIGHT, each side an integer in 16..4096, got '") + bad + "'");
    EXPECT_EQ(refusal(c, "--batch", "0"), "--batch wants an integer in 1..4096, got '0'");
    EXPECT_EQ(refusal(c, "--switch-off", "1.5"), "--switch-off wants a number in [0, 1], got '1.5'");
    EXPECT_EQ(refusal(c, "--coherence", "maybe"), "--coherence wants on or off, got 'maybe'");
    EXPECT_EQ(refusal(c, "--strategies", ","), "--strategies is empty");
    EXPECT_NE(refusal(c, "--driver", "voodoo").find("--driver: unknown driver 'voodoo'"), std::string::npos);
    EXPECT_NE(refusal(c, "--allocator", "glibc").find("--allocator"), std::string::npos);
    EXPECT_NE(refusal(c, "--make-databases", "some").find("--make-databases"), std::string::npos);
    // Nothing refused changed: the defaults stand.
    EXPECT_EQ(c.width, 512);
    EXPECT_EQ(c.height, 512);
    EXPECT_EQ(c.batch, 32);
    EXPECT_EQ(c.driver, gl::Driver::llvmpipe);
}

TEST(SessionCommandLine, ChecksStrategiesWithTheirSettings)
{
    SessionCommandLine c;
    EXPECT_NO_THROW(c.check_strategies({"vfc", "ou-shared"}));
    EXPECT_THROW(c.check_strategies({"vfc", "zbuffer-magic"}), std::invalid_argument);
    c.common = {"tolerance=0.5"};
    EXPECT_NO_THROW(c.check_strategies({"vfc", "ou"}));
    EXPECT_THROW(c.check_strategies({"vfc"}), std::invalid_argument);   // no chosen strategy has it
    c.common = {"tolerance=2"};
    EXPECT_THROW(c.check_strategies({"ou"}), std::invalid_argument);   // out of range
}
