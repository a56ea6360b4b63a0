#include <nori/common.h>
#include <cstdio>
int main() { std::puts("nori: under construction"); return 0; }
