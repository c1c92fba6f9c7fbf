set title 'GP fitness per generation (swimmer5)'
set xlabel 'generation'
set ylabel 'fitness'
set key bottom right
set grid
set terminal pngcairo size 900,600
set output 'fitness-swimmer5.png'
plot 'fitness-swimmer5.dat' index 0 using 1:2 with lines lw 2 lc 1 title 'best', 'fitness-swimmer5.dat' index 1 using 1:2 with lines lw 2 lc 2 title 'population mean'
set terminal svg size 900,600
set output 'fitness-swimmer5.svg'
plot 'fitness-swimmer5.dat' index 0 using 1:2 with lines lw 2 lc 1 title 'best', 'fitness-swimmer5.dat' index 1 using 1:2 with lines lw 2 lc 2 title 'population mean'
