// Captures the error messages an algorithm reports (vtkErrorMacro -> ErrorEvent), so
// tests can check them and the console stays quiet.
#pragma once

#include <vtkAlgorithm.h>
#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkObject.h>

#include <string>
#include <vector>

class ErrorCatcher : public vtkCommand
{
public:
  static ErrorCatcher* New() { return new ErrorCatcher; }
  void Execute(vtkObject*, unsigned long, void* callData) override
  {
    this->Messages.emplace_back(callData ? static_cast<const char*>(callData) : "");
  }
  std::string All() const
  {
    std::string all;
    for (const auto& m : this->Messages)
    {
      all += m + "\n";
    }
    return all;
  }
  std::vector<std::string> Messages;
};

/// Updates an algorithm and returns whether its pipeline request succeeded
/// (vtkAlgorithm::Update() returns nothing in VTK 9.1).
inline bool UpdateSucceeded(vtkAlgorithm* algorithm)
{
  return algorithm->GetExecutive()->Update() != 0;
}
