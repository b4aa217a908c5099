// CHECK_THROWS_AS_WITH(expr, Type, matcher): expr throws Type and its what() matches (Catch2 2.x has no single
// macro for both). The expression runs twice.
#pragma once

#include <catch2/catch.hpp>

#define CHECK_THROWS_AS_WITH(expr, type, matcher) \
  do {                                             \
    CHECK_THROWS_AS(expr, type);                   \
    CHECK_THROWS_WITH(expr, matcher);              \
  } while (false)
