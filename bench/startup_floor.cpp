// bench_startup's floor: a process that returns at once, so that the cost of starting any
// program on the machine at that moment is measured beside heavytop's.
int main() { return 0; }
