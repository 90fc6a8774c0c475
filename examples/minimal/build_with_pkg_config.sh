c++ -std=c++17 -O2 main.cc -o segment_video $(pkg-config --cflags --libs movseg)
