// EXPECT_MENTIONS(diag, what): the diagnostic's message says `what` (the
// whole diagnostic shown when it does not).
#pragma once

#include <gtest/gtest.h>

#include <string>

#define EXPECT_MENTIONS(diag, what) \
  EXPECT_NE((diag).message.find(what), std::string::npos) << (diag).to_string()
