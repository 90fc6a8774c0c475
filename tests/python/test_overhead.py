"""bench/python_overhead.py's measurement, held to its limit: Python adds under 5 % at 320x240."""
import importlib.util


def load_bench(source_dir):
    spec = importlib.util.spec_from_file_location("python_overhead", source_dir / "bench/python_overhead.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_python_overhead_is_under_five_percent(source_dir):
    bench = load_bench(source_dir)
    cpp, _, overhead = bench.measure(bench.synth_frames(12), rounds=1)
    assert overhead < 0.05 * cpp, f"overhead {overhead:.3f} ms vs C++ {cpp:.3f} ms"
