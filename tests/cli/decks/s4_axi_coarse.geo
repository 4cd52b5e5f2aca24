// A coarse S4-axi (Axisymmetric.S4AxiCoarseRecoilIsTheElasticSpringBack): the meridian
// section of inputs/s4_axi.geo with 2 wire turns instead of 8 and a coarser mesh (lumen
// 0.1 instead of 0.05, adventitia 0.3 instead of 0.15, 2 x 2 cells per wire instead of 4 x 4).
h = 0.1;
ho = 0.3;
ns = 2;
n = 2;
Include "../../../inputs/s4_axi.geo";
