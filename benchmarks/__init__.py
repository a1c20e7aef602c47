"""Benchmark scripts (not tests): ``PYTHONPATH=. python benchmarks/run_all.py [--quick]``."""
