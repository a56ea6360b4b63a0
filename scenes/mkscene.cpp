#include <cstdio>
int main(int argc, char **argv) { if (argc > 1) { FILE *f = std::fopen(argv[1], "w"); if (f) std::fclose(f); } return 0; }
