# Solver benchmark (included from Testing/Benchmarks/CMakeLists.txt). Prints throughput
# (particle-steps per second, memory per particle) and, with --sweep, speed against
# accuracy over Timestep Safety; see Documentation/Benchmarks-Solver.md.
add_executable(rockdem_bench_solver bench_solver.cpp)
target_link_libraries(rockdem_bench_solver PRIVATE RockDEM::solver)
target_compile_options(rockdem_bench_solver PRIVATE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic>)
# Smoke run (about 1 s): 2000 particles x 50 steps per pack and thread count, and a
# two-point sweep on reduced workloads. The real figures come from running it by hand.
add_test(NAME BenchSolverSmoke COMMAND rockdem_bench_solver --quick)
set_tests_properties(BenchSolverSmoke PROPERTIES TIMEOUT 60)
# The GPU backend (lavapipe in CI) beside the CPU on a small cemented specimen under
# compression (about 10 s); figures in Documentation/Benchmarks-GPU.md. Skipped (saying
# why) on a machine without a Vulkan device, as are all tests labelled gpu.
add_test(NAME BenchSolverGpuSmoke COMMAND rockdem_bench_solver --sizes 2000 --steps 50
         --packs cemented --backend cpu,gpu --threads 1)
set_tests_properties(BenchSolverGpuSmoke PROPERTIES TIMEOUT 120 LABELS gpu
  PASS_REGULAR_EXPRESSION "GPU Vulkan: .*device memory"
  SKIP_REGULAR_EXPRESSION "no usable Vulkan device on this machine")

# The press test on the CPU and the GPU, compared (scripts/gpu_check.sh runs it on an NVIDIA
# device; Documentation/Benchmarks-GPU.md). Smoke run: a small specimen on lavapipe.
add_executable(rockdem_gpu_parity gpu_parity.cpp)
target_include_directories(rockdem_gpu_parity PRIVATE "${PROJECT_SOURCE_DIR}/Testing/Solver")
target_link_libraries(rockdem_gpu_parity PRIVATE RockDEM::solver)
target_compile_options(rockdem_gpu_parity PRIVATE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic>)
add_test(NAME GpuParitySmoke COMMAND rockdem_gpu_parity --particles 300 --max-steps 1500)
set_tests_properties(GpuParitySmoke PROPERTIES TIMEOUT 120 LABELS gpu
  PASS_REGULAR_EXPRESSION "verdict: PASS \\(bitwise identical\\)" SKIP_RETURN_CODE 77)
