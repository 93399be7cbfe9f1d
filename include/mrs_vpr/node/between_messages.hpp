#pragma once

#include <functional>

namespace mrs_vpr {
namespace bag {

/// Called before a bag's first message is read and after each one (each transform, for /tf), but not
/// after the last one a read needs; it may throw to stop the read (a tool's Ctrl-C).
using BetweenMessages = std::function<void()>;

}  // namespace bag
}  // namespace mrs_vpr
