"""Evaluation: sweeps, executors, tables and figures."""
