#pragma once
namespace ra::low {
int upward();
}  // namespace ra::low
