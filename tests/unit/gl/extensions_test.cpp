// SPDX-License-Identifier: MIT
#include "gl/extensions.h"

#include <gtest/gtest.h>

using occu::gl::extension_in_list;

TEST(ExtensionInList, FindsWholeEntriesAnywhere)
{
    const char *list = "GL_ARB_a GL_MESAX_occlusion_unit GL_EXT_b";
    EXPECT_TRUE(extension_in_list(list, "GL_ARB_a"));
    EXPECT_TRUE(extension_in_list(list, "GL_MESAX_occlusion_unit"));
    EXPECT_TRUE(extension_in_list(list, "GL_EXT_b"));
}

TEST(ExtensionInList, RejectsPrefixesSuffixesAndInfixes)
{
    const char *list = "GL_ARB_occlusion_query2 GL_XGL_MESAX_occlusion_unit_x";
    EXPECT_FALSE(extension_in_list(list, "GL_ARB_occlusion_query"));
    EXPECT_FALSE(extension_in_list(list, "occlusion_query2"));
    EXPECT_FALSE(extension_in_list(list, "GL_MESAX_occlusion_unit"));
}

TEST(ExtensionInList, MatchAfterARejectedPartialOne)
{
    // The first occurrence is a prefix of another name; the second is whole.
    EXPECT_TRUE(extension_in_list("GL_foo_bar GL_foo", "GL_foo"));
}

TEST(ExtensionInList, EmptyInputs)
{
    EXPECT_FALSE(extension_in_list("", "GL_foo"));
    EXPECT_FALSE(extension_in_list("GL_foo", ""));
    EXPECT_FALSE(extension_in_list("  ", "GL_foo"));
}
