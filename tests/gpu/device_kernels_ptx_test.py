"""Every device kernel of gpu/device_models.cu stores each of its output columns.

nvcc compiles device code that reaches something undefined on the device (libstdc++'s strlen
builtin behind a std::string_view built from a literal was one) into an empty kernel body,
without an error or a warning. This reads the unit's PTX: one kernel per (device-capable model
of gpu/device_support.h, float or double, eval/pdf/sample), and each must contain at least one
global store per output column: eval value, pdf and its intermediates (at least 2), pdf 1,
sample 6 (wo, pdf, weight, rejected); and the Table 3 frame kernel (gpu/table3_frame.cu, one per
NDF: GGX and Beckmann) stores each pixel's radiance.
Usage: device_kernels_ptx_test.py gpu/device_support.h device_models.ptx table3_frame.ptx
"""
import re
import sys

MIN_STORES = {"eval": 2, "pdf": 1, "sample": 6, "frame": 1}


def main(support_header, *ptx_paths):
    header = open(support_header).read()
    table = header[header.index("kDeviceSupport"):]
    models = re.findall(r'\{"(\w+)", ""\}', table)
    # ctest passes the object list as one argument, separated by ';'.
    paths = [p for arg in ptx_paths for p in arg.split(";") if p]
    ptx = "".join(open(p).read() for p in paths)
    entries = re.findall(r"\.entry (\S+)\((.*?)\n\}\n", ptx, re.S)
    failures = []
    expected = 6 * len(models) + 2
    if len(entries) != expected:
        failures.append(f"{len(entries)} kernels in the PTX, expected {expected} "
                        f"(6 for each of {', '.join(models)}, 2 Table 3 frames)")
    for name, body in entries:
        kind = re.search(r"(eval|pdf|sample|frame)_kernel", name).group(1)
        stores = body.count("st.global")
        if stores < MIN_STORES[kind]:
            failures.append(f"{name}: {stores} global stores, a {kind} kernel writes at least "
                            f"{MIN_STORES[kind]} (an empty body: device code nvcc dropped)")
    for f in failures:
        print("FAIL:", f)
    print(f"{len(entries)} kernels for {len(models)} models; {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], *sys.argv[2:]))
