"""Benchmarks (not tests): ``python -m benchmarks.bench_kinematics``; see benchmarks/README.md."""
