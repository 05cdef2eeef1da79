// Which executable runs `worker` processes: renderaudit-worker beside the running program when it
// is there (it starts 20 times faster: app/worker_main.cpp), else the running program itself.
#pragma once

#include <string>

namespace ra::util {

std::string worker_program();

}  // namespace ra::util
