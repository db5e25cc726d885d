#pragma once
// Compiler-specific attributes of the library's hot paths (private to src/).

/// Turns GCC's loop vectorizer off for one function: for the small systems that dominate (2–20
/// states) its prologues cost more than they save. Clang has no such per-function switch: empty.
#if defined(__GNUC__) && !defined(__clang__)
#define MACHDYN_NO_TREE_VECTORIZE __attribute__((optimize("no-tree-vectorize")))
#else
#define MACHDYN_NO_TREE_VECTORIZE
#endif
