// Loads a generated controller library (dlopen) and makes its Controller.
#pragma once

#include <dlfcn.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "robot/controller.hpp"

namespace mospec::codegen::testing {

struct LoadedController {
  void* handle = nullptr;
  std::unique_ptr<robot::Controller> controller;
  LoadedController() = default;
  LoadedController(const LoadedController&) = delete;
  LoadedController& operator=(const LoadedController&) = delete;
  ~LoadedController() {
    controller.reset();  // its code lives in the library: destroy it first
    if (handle != nullptr) dlclose(handle);
  }
};

inline void load_controller(const std::string& path, LoadedController& out) {
  out.handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (out.handle == nullptr) throw std::runtime_error(std::string("dlopen: ") + dlerror());
  void* symbol = dlsym(out.handle, robot::kControllerFactorySymbol);
  if (symbol == nullptr) throw std::runtime_error(path + " exports no mospec_create_controller");
  const auto factory = reinterpret_cast<robot::ControllerFactory>(symbol);
  out.controller.reset(factory());
  if (out.controller->abi_version() != robot::kControllerAbiVersion) {
    throw std::runtime_error(path + " was built against another Controller ABI");
  }
}

// The library path from an environment variable the build test sets.
inline std::string library_from_env(const char* variable) {
  const char* v = std::getenv(variable);
  return v != nullptr ? std::string(v) : std::string();
}

}  // namespace mospec::codegen::testing
