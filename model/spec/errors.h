// The error type of bad input: a model file, an override or a spec that cannot be built into a model.
#pragma once

#include <stdexcept>

namespace turbodyn {

/// A problem with a model file or an override. what() is the complete message for the user.
class ModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace turbodyn
