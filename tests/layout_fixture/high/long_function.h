#pragma once
namespace ra::high {
int long_function(int x);
int long_but_whole(int x);
}  // namespace ra::high
