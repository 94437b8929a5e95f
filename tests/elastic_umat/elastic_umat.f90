!> A tiny linear-elastic Abaqus UMAT (isotropic; PROPS: E, nu; no state variables), linked into a
!> second driver executable to show that any UMAT with the standard argument list can replace
!> Cam-Clay IX. STRESS = STRESS + C:DSTRAN, DDSDDE = C (engineering shear strains).
subroutine umat(stress, statev, ddsdde, sse, spd, scd, rpl, ddsddt, drplde, drpldt, &
                stran, dstran, time, dtime, temp, dtemp, predef, dpred, cmname, &
                ndi, nshr, ntens, nstatv, props, nprops, coords, drot, pnewdt, &
                celent, dfgrd0, dfgrd1, noel, npt, layer, kspt, jstep, kinc)
  use, intrinsic :: iso_fortran_env, only: real64
  implicit none
  character(len=80), intent(in) :: cmname
  integer, intent(in) :: ndi, nshr, ntens, nstatv, nprops, noel, npt, layer, kspt, jstep(*), kinc
  real(real64), intent(inout) :: stress(ntens), statev(*), sse, spd, scd, pnewdt
  real(real64), intent(out) :: ddsdde(ntens, ntens), rpl, ddsddt(ntens), drplde(ntens), drpldt
  real(real64), intent(in) :: stran(ntens), dstran(ntens), time(2), dtime, temp, dtemp, predef(*), dpred(*), &
                              props(nprops), coords(3), drot(3, 3), celent, dfgrd0(3, 3), dfgrd1(3, 3)
  real(real64) :: lam, mu
  integer :: i
  lam = props(1) * props(2) / ((1 + props(2)) * (1 - 2 * props(2)))
  mu = props(1) / (2 * (1 + props(2)))
  ddsdde = 0
  ddsdde(1:ndi, 1:ndi) = lam
  do i = 1, ndi
    ddsdde(i, i) = lam + 2 * mu
  end do
  do i = ndi + 1, ntens
    ddsdde(i, i) = mu
  end do
  stress = stress + matmul(ddsdde, dstran)
  rpl = 0; ddsddt = 0; drplde = 0; drpldt = 0
end subroutine umat
